#include "glint/render/film/film.h"

namespace glint {

Image8 toImage8(const Film& film) { return toImage8With(film, toByte); }

void FilmSums::add(const FilmSums& other) {
    for (size_t i = 0; i < sums_.size() && i < other.sums_.size(); ++i) {
        sums_[i].add(other.sums_[i]);
        weights_[i] += other.weights_[i];
    }
    for (size_t i = 0; i < passes_.size() && i < other.passes_.size(); ++i)
        passes_[i] += other.passes_[i];
}

void resolvePassesAt(const Vec3& sum, double n, const PassSums& p, RenderPasses& out, size_t i) {
    if (!(n > 0)) {
        out.albedo[i] = out.normal[i] = out.variance[i] = out.albedoVariance[i] = Vec3(0);
        out.depth[i] = 0;
        return;
    }
    const double inv = 1.0 / n;
    out.albedo[i] = p.albedo * inv;
    out.normal[i] = p.normal * inv;
    out.depth[i] = p.hits > 0 ? p.depth / p.hits : 0;
    if (n < 2) {
        out.variance[i] = out.albedoVariance[i] = Vec3(0);
        return;
    }
    // The sample variance (n / (n - 1)) (E[x^2] - E[x]^2), over n for the mean's.
    auto varianceOfMean = [&](const Vec3& mean, const Vec3& squares) {
        Vec3 v = (squares * inv - mean * mean) * (1.0 / (n - 1));
        for (int c = 0; c < 3; ++c) v[c] = v[c] > 0 ? v[c] : 0;
        return v;
    };
    out.variance[i] = varianceOfMean(sum * inv, p.squares);
    out.albedoVariance[i] = varianceOfMean(out.albedo[i], p.albedoSquares);
}

RenderPasses FilmSums::resolvePasses() const {
    if (passes_.empty()) return {};
    RenderPasses out(width_, height_);
    for (size_t i = 0; i < size(); ++i)
        resolvePassesAt(sums_[i].value(), weights_[i], passes_[i], out, i);
    return out;
}

Film FilmSums::resolve() const {
    Film film(width_, height_);
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x)
            film.at(x, y) = pixelValue(sum(x, y).value(), weight(x, y));
    return film;
}

std::string parseAovList(const std::string& text, AovSelection& out) {
    AovSelection sel;
    if (text == "all") {
        out = AovSelection::all();
        return {};
    }
    size_t at = 0;
    for (;;) {
        const size_t comma = text.find(',', at);
        const std::string name = text.substr(at, comma == std::string::npos ? comma : comma - at);
        if (name == "albedo")
            sel.albedo = true;
        else if (name == "normal")
            sel.normal = true;
        else if (name == "depth")
            sel.depth = true;
        else if (name == "variance")
            sel.variance = true;
        else
            return "unknown pass '" + name +
                   "' (Glint has albedo, normal, depth, variance; or all)";
        if (comma == std::string::npos) break;
        at = comma + 1;
    }
    out = sel;
    return {};
}

std::string aovListText(const AovSelection& aovs) {
    std::string out;
    auto add = [&](bool on, const char* name) {
        if (!on) return;
        if (!out.empty()) out += ',';
        out += name;
    };
    add(aovs.albedo, "albedo");
    add(aovs.normal, "normal");
    add(aovs.depth, "depth");
    add(aovs.variance, "variance");
    return out;
}

}  // namespace glint
