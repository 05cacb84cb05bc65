// Scene-file commands for participating media (docs/scene-format.md, "Media"): `medium` names
// one, `interior` puts one inside the current material's closed surfaces, `fog` fills the
// scene with one.

#include <cmath>

#include "glint/io/course/course_parser.h"
#include "glint/io/vdb/vdb_reader.h"

namespace glint::course {

namespace {

/// Whether `word` is one of the medium command's parameter names.
bool isKeyword(std::string_view word) {
    for (const char* k :
         {"absorption", "scattering", "albedo", "meanfreepath", "g", "density", "scale"})
        if (word == k) return true;
    return false;
}

}  // namespace

void Parser::cmdMedium() {
    const std::string name(tok_[1].text);
    if (name == "none") fail(1, "'none' names no medium; choose another name");
    Medium m;
    m.name = name;
    Vec3 albedo(-1);
    double meanFree = 0, scale = 1;
    for (int i = 2; i < ntok_;) {
        const std::string_view key = tok_[i].text;
        auto need = [&](int n) {
            if (i + n >= ntok_)
                fail(i, "medium '" + std::string(key) + "' needs " + std::to_string(n) +
                            (n == 1 ? " number" : " numbers"));
        };
        auto nonNegative = [&](int k) {
            const double x = real(k);
            if (!(x >= 0)) fail(k, std::string(key) + " must not be negative, got " + quoted(k));
            return x;
        };
        if (key == "absorption" || key == "scattering") {
            need(3);
            const Vec3 c(nonNegative(i + 1), nonNegative(i + 2), nonNegative(i + 3));
            (key == "absorption" ? m.sigmaA : m.sigmaS) = c;
            i += 4;
        } else if (key == "albedo") {
            need(3);
            albedo = unitColour(i + 1, "albedo");
            i += 4;
        } else if (key == "meanfreepath") {
            need(1);
            meanFree = real(i + 1);
            if (!(meanFree > 0)) fail(i + 1, "meanfreepath must be positive, got " + quoted(i + 1));
            i += 2;
        } else if (key == "g") {
            need(1);
            m.g = real(i + 1);
            if (!(m.g > -1 && m.g < 1))
                fail(i + 1, "g must be between -1 and 1, got " + quoted(i + 1));
            i += 2;
        } else if (key == "density") {  // density file.vdb [grid]
            need(1);
            if (!limits_.readFiles)
                fail(i + 1, "density grid " + quoted(i + 1) + " is not read: reading files is off");
            const bool named = i + 2 < ntok_ && !isKeyword(tok_[i + 2].text);
            try {
                m.grid = loadVdbDensity(scenePath(tok_[i + 1].text),
                                        named ? std::string(tok_[i + 2].text) : "", limits_);
            } catch (const RenderError& e) {
                fail(i + 1, e.what());
            }
            std::optional<Transform> placed =
                Transform::fromMatrix(transform().matrix() * m.grid->worldFromIndex.matrix());
            if (!placed) fail(i + 1, "the current transform makes the grid singular");
            m.worldFromIndex = *placed;
            m.densityBound = m.grid->maxDensity();
            m.majorants = std::make_shared<const MajorantGrid>(*m.grid);
            i += named ? 3 : 2;
        } else if (key == "scale") {
            need(1);
            scale = nonNegative(i + 1);
            i += 2;
        } else {
            fail(i, "unknown medium parameter " + quoted(i) +
                        " (absorption, scattering, albedo, meanfreepath, g, density, scale)");
        }
    }
    if ((albedo.x >= 0) != (meanFree > 0)) fail(0, "medium: albedo and meanfreepath go together");
    if (meanFree > 0) {  // sigma_t = 1 / mean free path, split by the single-scattering albedo
        m.sigmaS = albedo / meanFree;
        m.sigmaA = (Vec3(1) - albedo) / meanFree;
    }
    m.sigmaA = m.sigmaA * scale;
    m.sigmaS = m.sigmaS * scale;
    if (!std::isfinite(maxComponent(m.sigmaA + m.sigmaS)))
        fail(0, "medium: its coefficients are too large");
    media_[name] = scene().addMedium(std::move(m));
}

uint32_t Parser::mediumNamed(int token) const {
    if (tok_[token].text == "none") return 0;
    auto it = media_.find(std::string(tok_[token].text));
    if (it == media_.end())
        fail(token, "no medium named " + quoted(token) + " (define it with 'medium' first)");
    return it->second;
}

void Parser::cmdInterior() {
    Material& m = builder_.editMaterial();
    m.interior = mediumNamed(1);
    m.interface = false;
    if (ntok_ > 2) {
        if (tok_[2].text != "interface")
            fail(2, "expected 'interface' or nothing, got " + quoted(2));
        if (m.interior == 0) fail(2, "'interior none' has no boundary to draw or hide");
        m.interface = true;
    }
}

void Parser::cmdFog() { scene().fog = mediumNamed(1); }

}  // namespace glint::course
