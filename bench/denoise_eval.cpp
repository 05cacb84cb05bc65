// denoise_eval: measures the denoiser (src/glint/denoise) on a set of noisy render buffers and
// prints the relative MSE against a reference before and after, and the time of denoise().
//
//   denoise_eval DIR NAME SPP [key=value ...]
//       reads DIR/NAME_SPP.pfm (colour), NAME_SPP.{albedo,normal,depth,variance,albedoVariance}.pfm
//       (those present) and DIR/NAME_ref.pfm; writes DIR/NAME_SPP.denoised.pfm unless out=none.
//   denoise_eval synth WIDTH HEIGHT SPP [key=value ...]
//       the same on a synthetic scene (a textured floor, spheres, a hard shadow, a sky) with
//       heavy-tailed per-sample noise; also prints the raw error at 32x the samples.
//
// Keys: ref=PATH (another reference), threads=N (2), runs=N (timing runs, the median is printed;
// 1), out=PATH|none, denoiser=nlm|oidn (nlm: the parameters below apply; oidn: the network,
// quality=fast|balanced|high; its output NAME_SPP.oidn-QUALITY.pfm), and the parameters of
// denoise_detail::DenoiseTuning: r1 p1 k1 al1 n1 a1 d1 fo1 ridge1 (first pass: radius, patch, k,
// alpha, normal, albedo, depth weights, first order 0/1, its ridge), r2 ... ridge2 (second; r2=0:
// one pass), gvs (second guide's variance scale), sov (second guide's outlier variance), vr
// (variance smoothing radius), ov (outlier variance ratio), evs (estimated variance scale), af
// (albedo floor), ra ... ridgea (the albedo's filter; ra=0: none), fire=P (synthetic: the
// probability of a firefly sample, 0.001), and noalbedo=1 nonormal=1 nodepth=1 novariance=1
// noalbedovariance=1 to leave a buffer out; png=PATH writes raw | nlm | the network (quality) |
// reference side by side, as the model mode shows them (crop=X,Y,W,H[,ZOOM]: that part, enlarged).
// relMSE = mean over pixels and channels of (x - ref)^2 / (ref^2 + 0.01).

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "glint/core/error.h"
#include "glint/denoise/denoise.h"
#include "glint/denoise/metrics.h"
#include "glint/denoise/network_denoise.h"
#include "glint/denoise/tuning.h"
#include "glint/io/image/image_io.h"
#include "glint/math/rng.h"

using namespace glint;

namespace {

struct Buffers {
    int width = 0, height = 0;
    std::vector<Vec3> color, albedo, normal, variance, albedoVariance, reference, reference32;
    std::vector<double> depth;
};

// ---- The synthetic scene: ray cast once per pixel centre.
struct Sphere {
    Vec3 c;
    double r;
};
const Sphere kSpheres[] = {{{0, 0.5, 0}, 0.5}, {{-1.0, 0.3, -0.6}, 0.3}, {{0.9, 0.2, 0.5}, 0.2}};

double hitSphere(const Sphere& s, const Vec3& o, const Vec3& d) {
    const Vec3 oc = o - s.c;
    const double b = dot(oc, d), c = dot(oc, oc) - s.r * s.r, disc = b * b - c;
    if (disc < 0) return -1;
    const double t = -b - std::sqrt(disc);
    return t > 1e-6 ? t : -1;
}

struct Clean {
    Vec3 color, albedo, normal;
    double depth = 0;
};

Clean shade(const Vec3& o, const Vec3& d) {
    const Vec3 light = normalize(Vec3(1, 2, 0.8));
    double best = 1e30;
    int hit = -1;
    for (int i = 0; i < 3; ++i) {
        const double t = hitSphere(kSpheres[i], o, d);
        if (t > 0 && t < best) best = t, hit = i;
    }
    if (d.y < 0) {
        const double t = -o.y / d.y;
        if (t < best) best = t, hit = 3;
    }
    Clean r;
    if (hit < 0) {
        r.color = Vec3(0.4, 0.6, 1.0) * (0.6 + 0.4 * d.y);
        return r;
    }
    const Vec3 p = o + d * best;
    Vec3 n;
    Vec3 albedo;
    if (hit == 3) {
        n = Vec3(0, 1, 0);
        const bool check =
            (static_cast<int>(std::floor(p.x * 2)) + static_cast<int>(std::floor(p.z * 2))) & 1;
        const double fine = 0.5 + 0.5 * std::sin(p.x * 40) * std::sin(p.z * 40);
        albedo = check ? Vec3(0.75, 0.7, 0.6) : Vec3(0.15, 0.2, 0.3);
        albedo = albedo * (0.8 + 0.2 * fine);
    } else {
        n = normalize(p - kSpheres[hit].c);
        if (hit == 0) {
            const double stripes = std::sin(std::atan2(n.z, n.x) * 24) > 0 ? 1.0 : 0.3;
            albedo = Vec3(0.8, 0.8, 0.8) * stripes;
        } else {
            albedo = hit == 1 ? Vec3(0.8, 0.2, 0.2) : Vec3(0.2, 0.7, 0.3);
        }
    }
    bool shadow = false;
    for (const Sphere& s : kSpheres)
        if (hitSphere(s, p + n * 1e-4, light) > 0) shadow = true;
    const double direct = shadow ? 0 : std::max(0.0, dot(n, light)) * 2.5;
    const double ambient = 0.25 * (0.6 + 0.4 * n.y);
    r.color = albedo * (direct + ambient);
    if (hit == 0 && !shadow) {  // a glossy highlight, not multiplied by albedo
        const Vec3 refl = d - n * (2 * dot(d, n));
        r.color += Vec3(std::pow(std::max(0.0, dot(refl, light)), 40) * 3);
    }
    r.albedo = albedo;
    r.normal = n;
    r.depth = best;
    return r;
}

// Mean and variance of the mean of `spp` heavy-tailed samples: clean times Z, E[Z] = 1, Z an
// exponential variable with rare fireflies 100 times the mean, and a little chroma noise.
double gFireflies = 0.001;  // the probability of a firefly sample (key fire=)

void noisy(const std::vector<Vec3>& clean, int spp, uint64_t seed, std::vector<Vec3>& mean,
           std::vector<Vec3>* variance) {
    mean.assign(clean.size(), Vec3(0));
    if (variance) variance->assign(clean.size(), Vec3(0));
    const double pf = gFireflies, fire = 100, base = (1 - pf * fire) / (1 - pf);
    for (size_t i = 0; i < clean.size(); ++i) {
        Rng rng(seed * 0x9E3779B97F4A7C15ULL + i);
        Vec3 s(0), s2(0);
        for (int k = 0; k < spp; ++k) {
            double z = rng.uniform() < pf ? fire : -std::log(1.0 - rng.uniform()) * base;
            Vec3 v;
            for (int c = 0; c < 3; ++c) v[c] = clean[i][c] * z * (0.8 + 0.4 * rng.uniform());
            s += v;
            s2 += v * v;
        }
        mean[i] = s * (1.0 / spp);
        if (variance)
            for (int c = 0; c < 3; ++c)
                (*variance)[i][c] =
                    spp > 1 ? std::max(0.0, (s2[c] - s[c] * s[c] / spp) / (spp - 1)) / spp : 0;
    }
}

Buffers synthetic(int width, int height, int spp) {
    Buffers b;
    b.width = width, b.height = height;
    const size_t n = static_cast<size_t>(width) * height;
    b.albedo.resize(n), b.normal.resize(n), b.depth.resize(n), b.reference.resize(n);
    const Vec3 eye(0, 1.1, 3.2), at(0, 0.4, 0);
    const Vec3 w = normalize(eye - at), u = normalize(cross(Vec3(0, 1, 0), w)), v = cross(w, u);
    const double tanHalf = std::tan(0.5 * 50 * 3.14159265 / 180), aspect = double(width) / height;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const double sx = (2 * (x + 0.5) / width - 1) * tanHalf * aspect;
            const double sy = (1 - 2 * (y + 0.5) / height) * tanHalf;
            const Clean c = shade(eye, normalize(u * sx + v * sy - w));
            const size_t i = static_cast<size_t>(y) * width + x;
            b.reference[i] = c.color, b.albedo[i] = c.albedo, b.normal[i] = c.normal;
            b.depth[i] = c.depth;
        }
    noisy(b.reference, spp, 1, b.color, &b.variance);
    noisy(b.reference, spp * 32, 2, b.reference32, nullptr);
    return b;
}

Buffers load(const std::string& dir, const std::string& name, const std::string& spp,
             const std::string& reference) {
    Buffers b;
    const std::string base = dir + "/" + name + "_" + spp;
    Film color = readPfm(base + ".pfm");
    b.width = color.width(), b.height = color.height();
    b.color = color.pixels();
    auto optional = [&](const std::string& what) {
        const std::string path = base + "." + what + ".pfm";
        return std::filesystem::exists(path) ? readPfm(path).pixels() : std::vector<Vec3>{};
    };
    b.albedo = optional("albedo");
    b.normal = optional("normal");
    b.variance = optional("variance");
    b.albedoVariance = optional("albedoVariance");
    for (const Vec3& d : optional("depth")) b.depth.push_back(d.x);
    b.reference = readPfm(reference.empty() ? dir + "/" + name + "_ref.pfm" : reference).pixels();
    return b;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 4) {
        std::fprintf(stderr,
                     "usage: denoise_eval DIR NAME SPP [key=value ...]\n"
                     "       denoise_eval synth WIDTH HEIGHT SPP [key=value ...]\n");
        return 2;
    }
    const bool synth = std::string(argv[1]) == "synth";
    const int firstKey = synth ? 5 : 4;
    std::map<std::string, std::string> keys;
    for (int i = firstKey; i < argc; ++i) {
        const std::string a = argv[i];
        const size_t eq = a.find('=');
        if (eq == std::string::npos) {
            std::fprintf(stderr, "denoise_eval: expected key=value, got '%s'\n", a.c_str());
            return 2;
        }
        keys[a.substr(0, eq)] = a.substr(eq + 1);
    }
    auto num = [&](const char* k, double fallback) {
        auto it = keys.find(k);
        return it == keys.end() ? fallback : std::atof(it->second.c_str());
    };
    denoise_detail::DenoiseTuning t;
    auto pass = [&](denoise_detail::NlMeansParams& p, const std::string& s) {
        p.radius = static_cast<int>(num(("r" + s).c_str(), p.radius));
        p.patch = static_cast<int>(num(("p" + s).c_str(), p.patch));
        p.k = static_cast<float>(num(("k" + s).c_str(), p.k));
        p.alpha = static_cast<float>(num(("al" + s).c_str(), p.alpha));
        p.normalWeight = static_cast<float>(num(("n" + s).c_str(), p.normalWeight));
        p.albedoWeight = static_cast<float>(num(("a" + s).c_str(), p.albedoWeight));
        p.depthWeight = static_cast<float>(num(("d" + s).c_str(), p.depthWeight));
        p.firstOrder = num(("fo" + s).c_str(), p.firstOrder) != 0;
        p.ridge = static_cast<float>(num(("ridge" + s).c_str(), p.ridge));
    };
    pass(t.first, "1");
    pass(t.second, "2");
    pass(t.albedo, "a");  // the albedo's filter: ra=0 turns it off
    t.secondGuideVarianceScale = static_cast<float>(num("gvs", t.secondGuideVarianceScale));
    t.varianceRadius = static_cast<int>(num("vr", t.varianceRadius));
    t.estimatedVarianceScale = static_cast<float>(num("evs", t.estimatedVarianceScale));
    t.outlierVariance = static_cast<float>(num("ov", t.outlierVariance));
    t.albedoFloor = static_cast<float>(num("af", t.albedoFloor));
    t.secondOutlierVariance = static_cast<float>(num("sov", t.secondOutlierVariance));

    gFireflies = num("fire", gFireflies);
    Buffers b;
    std::string out;
    try {
        if (synth) {
            b = synthetic(std::atoi(argv[2]), std::atoi(argv[3]), std::atoi(argv[4]));
            out = "/tmp/denoise_synth_" + std::string(argv[4]) + ".pfm";
        } else {
            b = load(argv[1], argv[2], argv[3], keys.count("ref") ? keys["ref"] : "");
            out = std::string(argv[1]) + "/" + argv[2] + "_" + argv[3] + ".denoised.pfm";
        }
    } catch (const RenderError& e) {
        std::fprintf(stderr, "denoise_eval: %s\n", e.what());
        return 1;
    }
    if (keys.count("out")) out = keys["out"];

    DenoiseInput in;
    in.width = b.width, in.height = b.height, in.color = b.color.data();
    if (!b.albedo.empty() && !num("noalbedo", 0)) in.albedo = b.albedo.data();
    if (!b.normal.empty() && !num("nonormal", 0)) in.normal = b.normal.data();
    if (!b.depth.empty() && !num("nodepth", 0)) in.depth = b.depth.data();
    if (!b.variance.empty() && !num("novariance", 0)) in.variance = b.variance.data();
    if (!b.albedoVariance.empty() && !num("noalbedovariance", 0))
        in.albedoVariance = b.albedoVariance.data();
    ThreadPool pool(static_cast<int>(num("threads", 2)));
    DenoiseOptions options;
    options.pool = &pool;
    std::vector<Vec3> result;
    std::vector<double> seconds;
    const bool network = keys.count("denoiser") && keys["denoiser"] == "oidn";
    const DenoiseQuality quality =
        denoiseQualityNamed(keys.count("quality") ? keys["quality"] : "balanced");
    if (network && !synth && !keys.count("out"))
        out = std::string(argv[1]) + "/" + argv[2] + "_" + argv[3] + ".oidn-" +
              std::string(denoiseQualityName(quality)) + ".pfm";
    for (int run = 0; run < std::max(1, static_cast<int>(num("runs", 1))); ++run) {
        const auto start = std::chrono::steady_clock::now();
        result = network ? networkDenoise(in, quality, pool).color
                         : denoise_detail::denoiseTuned(in, options, t);
        seconds.push_back(
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    std::sort(seconds.begin(), seconds.end());
    const double raw = relMse(b.color, b.reference), den = relMse(result, b.reference);
    std::printf(
        "%dx%d  relMSE raw %.5f  denoised %.5f  gain %.1fx  trimmed raw %.5f  "
        "denoised %.5f",
        b.width, b.height, raw, den, raw / den, relMseTrimmed(b.color, b.reference),
        relMseTrimmed(result, b.reference));
    if (!b.reference32.empty())
        std::printf("  (raw at 32x spp %.5f: goal gain %.1fx)", relMse(b.reference32, b.reference),
                    raw / relMse(b.reference32, b.reference));
    std::printf("  detail raw %.3f  denoised %.3f",
                detailKept(b.color, b.reference, b.width, b.height),
                detailKept(result, b.reference, b.width, b.height));
    std::printf("  mean/input %.4f  mean/ref %.4f  time %.3f s (%d threads)\n",
                meanValue(result) / meanValue(b.color), meanValue(result) / meanValue(b.reference),
                seconds[seconds.size() / 2], pool.threads());
    if (out != "none") {
        writeImage(out, Film(b.width, b.height, result));
    }
    if (keys.count("png")) {
        // raw | the filter | the network (at `quality`) | reference, side by side, as the model
        // mode shows an image (PBR Neutral, sRGB): the docs' pictures.
        const std::vector<Vec3> nlm =
            network ? denoise_detail::denoiseTuned(in, options, t) : result;
        const std::vector<Vec3> net = network ? result : networkDenoise(in, quality, pool).color;
        const std::vector<Vec3>* panels[] = {&b.color, &nlm, &net, &b.reference};
        int cx = 0, cy = 0, cw = b.width, ch = b.height, zoom = 1;  // crop=X,Y,W,H[,ZOOM]
        if (keys.count("crop"))
            std::sscanf(keys["crop"].c_str(), "%d,%d,%d,%d,%d", &cx, &cy, &cw, &ch, &zoom);
        cx = std::clamp(cx, 0, b.width - 1), cy = std::clamp(cy, 0, b.height - 1);
        cw = std::clamp(cw, 1, b.width - cx), ch = std::clamp(ch, 1, b.height - cy);
        zoom = std::clamp(zoom, 1, 8);
        Film f(4 * cw * zoom, ch * zoom);
        for (int k = 0; k < 4; ++k)
            for (int y = 0; y < ch * zoom; ++y)
                for (int x = 0; x < cw * zoom; ++x)
                    f.at((k * cw) * zoom + x, y) =
                        (*panels[k])[static_cast<size_t>(cy + y / zoom) * b.width + cx + x / zoom];
        writeImage(keys["png"], f, {0, true, ToneMap::PbrNeutral});
    }
    return 0;
}
