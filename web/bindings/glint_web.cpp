// The web page's view of Glint (embind): scenes and models read from the module's virtual file
// system by the same loaders as the command line, errors as the command line prints them, and a
// render that advances a few tiles per call, so that the Web Worker running it returns to its
// event loop between calls (to post the image, and to hear Cancel). web/src/worker.js drives it;
// docs/web.md describes the whole.
//
// Pixels are the library's: the traversal kernels are the SIMD128 ones (bit for bit the portable
// and the AVX2 ones), and a render of one pass at the scene's samples is the command line's
// render, so renderFile() writes the PNG file `glint SCENE -o OUT` writes (the Node test checks
// it byte for byte).

#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "glint/core/error.h"
#include "glint/core/parallel.h"
#include "glint/denoise/film_denoise.h"
#include "glint/denoise/network_denoise.h"
#include "glint/denoise/unet/tza.h"
#include "glint/denoise/unet/weights.h"
#include "glint/io/course/course_loader.h"
#include "glint/io/image/image_io.h"
#include "glint/io/registry.h"
#include "glint/render/film/display.h"
#include "glint/render/integrators/integrator.h"
#include "glint/render/progressive.h"
#include "glint/render/renderer.h"

namespace glint::web {
namespace {

using emscripten::val;
using Clock = std::chrono::steady_clock;

constexpr int kTile = 16;  // tile side, as the command line's

val diagnosticValue(const Diagnostic& d, const char* kind) {
    val o = val::object();
    o.set("file", d.loc.file);
    o.set("line", d.loc.line);
    o.set("column", d.loc.column);
    o.set("message", d.message);
    o.set("text", d.format(kind));
    return o;
}

val vecValue(const Vec3& v) {
    val a = val::array();
    a.call<void>("push", v.x, v.y, v.z);
    return a;
}

Vec3 toVec(const val& a) { return {a[0].as<double>(), a[1].as<double>(), a[2].as<double>()}; }

/// The first key of the animation `which` names (an index from 0, or a name; empty: the first),
/// or 0 when none is named so (the loader then says why).
double startOf(const std::vector<ModelAnimation>& animations, const std::string& which) {
    if (which.empty()) return animations.empty() ? 0 : animations[0].start;
    if (std::all_of(which.begin(), which.end(), [](char c) { return c >= '0' && c <= '9'; })) {
        const size_t i = which.size() < 10 ? std::stoul(which) : animations.size();
        return i < animations.size() ? animations[i].start : 0;
    }
    for (const ModelAnimation& a : animations)
        if (a.name == which) return a.start;
    return 0;
}

/// Whether two cameras look from the same eye at the same point with the same up (what the
/// page's orbit moves).
bool sameView(const CameraSpec& a, const CameraSpec& b) {
    return a.eye == b.eye && a.center == b.center && a.up == b.up;
}

/// Moves `to` to look as `from` does (the orbit's part of a camera: eye, center, up).
void setView(CameraSpec& to, const CameraSpec& from) {
    to.eye = from.eye;
    to.center = from.center;
    to.up = from.up;
}

int intOr(const val& o, const char* key, int fallback) {
    val v = o[key];
    return v.isNumber() ? v.as<int>() : fallback;
}

/// The error of an exception the loaders or the renderer threw, as the page shows it.
val errorValue(const std::exception& e) {
    if (auto* s = dynamic_cast<const SceneError*>(&e))
        return diagnosticValue(s->diagnostic(), "error");
    val o = val::object();
    o.set("file", std::string());
    o.set("line", 0);
    o.set("column", 0);
    o.set("message", std::string(e.what()));
    o.set("text", std::string("error: ") + e.what());
    return o;
}

}  // namespace

/// One scene at a time, its renders, and the threads they run on.
class Session {
  public:
    explicit Session(int threads) : pool_(std::max(1, threads)) {}

    int threads() const { return pool_.threads(); }

    /// Reads the scene or model file at `path` as `glint FILE` does, with options
    /// {integrator, lenient, width, height, prepare, kernels, animation, time, variant, reuse}:
    /// `variant` is a glTF model's material variant (KHR_materials_variants), as --variant;
    /// prepare
    /// (default true) builds its BVH for rendering; false only checks it (the editor, as you
    /// type). A model's animation plays as `glint FILE --animation A --time-at T` plays it:
    /// `animation` is its index (from 0) or name (default the first), `time` the file's seconds,
    /// or "start" for the animation's first key (a file without animations stays still);
    /// without `time` nothing plays. With `reuse` (the files are unchanged since the last load:
    /// the same file at a new time, or in a new look) model files parsed then are posed again
    /// instead of read again, and a camera that setCamera() moved stays where it was put.
    /// Returns {ok, error, warnings, note, width, height, spp, maxDepth, integrator,
    /// animations: [{name, start, end, channels}], animation (the index played, or null), time
    /// (the seconds posed, or null), variants (the names of a model's material variants)}.
    val load(const std::string& path, const val& options) {
        val r = val::object();
        val warningList = val::array();
        std::vector<Diagnostic> warnings;
        std::unique_ptr<Scene> scene;
        const bool reuse = options["reuse"].isTrue();
        if (!reuse) assets_ = std::make_unique<AssetCache>();  // files may have changed since
        std::optional<CameraSpec> moved;  // the page's view of the scene being posed anew
        if (reuse && scene_ && !sameView(*scene_->camera, home_)) moved = *scene_->camera;
        try {
            LoadOptions lo;
            lo.lenient = options["lenient"].isTrue();
            lo.width = std::max(0, intOr(options, "width", 0));  // a model's framing, as --size
            lo.height = std::max(0, intOr(options, "height", 0));
            val integrator = options["integrator"];
            if (integrator.isString()) lo.look.studio = integrator.as<std::string>() != "whitted";
            lo.assets = assets_.get();
            if (options["variant"].isString()) lo.variant = options["variant"].as<std::string>();
            val animation = options["animation"], time = options["time"];
            if (animation.isNumber())
                lo.time.animation = std::to_string(std::max(0, animation.as<int>()));
            else if (animation.isString())
                lo.time.animation = animation.as<std::string>();
            if (time.isNumber()) {
                lo.time.seconds = time.as<double>();
                if (!(std::abs(*lo.time.seconds) <= 1e6))  // as --time-at
                    throw RenderError("the time must be between -1e6 and 1e6 seconds");
            }
            ModelScene m = loadSceneFile(path, warnings, lo);
            if (time.isString() && time.as<std::string>() == "start" && !m.animations.empty()) {
                // Posed at its animation's first key, from the file parsed just now (a scene
                // file, whose models' animations are not listed, stays as `glint FILE` has it).
                lo.time.seconds = startOf(m.animations, lo.time.animation);
                std::vector<Diagnostic> posing;
                m = loadSceneFile(path, posing, lo);
                for (Diagnostic& d : posing)
                    if (std::none_of(warnings.begin(), warnings.end(), [&](const Diagnostic& w) {
                            return w.format("warning") == d.format("warning");
                        }))
                        warnings.push_back(std::move(d));
            }
            scene = std::move(m.scene);
            r.set("note", m.note);
            val animations = val::array();
            for (const ModelAnimation& a : m.animations) {
                val o = val::object();
                o.set("name", a.name);
                o.set("start", a.start);
                o.set("end", a.end);
                o.set("channels", static_cast<double>(a.channels));
                animations.call<void>("push", o);
            }
            r.set("animations", animations);
            val variants = val::array();
            for (const std::string& v : m.variants) variants.call<void>("push", v);
            r.set("variants", variants);
            r.set("animation", m.animation ? val(static_cast<double>(*m.animation)) : val::null());
            r.set("time", m.animation ? val(*lo.time.seconds) : val::null());
            if (!scene->camera) throw RenderError("the scene has no camera");
            if (!options["prepare"].isFalse())
                scene->prepare({&pool_, Bvh::named(options["kernels"].isString()
                                                       ? options["kernels"].as<std::string>()
                                                       : "")});
            r.set("ok", true);
            r.set("error", val::null());
        } catch (const std::exception& e) {
            r.set("ok", false);
            r.set("error", errorValue(e));
            scene.reset();
        }
        for (const Diagnostic& w : warnings)
            warningList.call<void>("push", diagnosticValue(w, "warning"));
        r.set("warnings", warningList);
        if (!scene) return r;
        r.set("width", scene->width);
        r.set("height", scene->height);
        r.set("spp", scene->spp);
        r.set("maxDepth", scene->maxDepth);
        r.set("integrator", scene->integrator);
        if (scene->prepared()) {
            integrator_.reset();  // of the scene replaced
            scene_ = std::move(scene);
            home_ = *scene_->camera;
            loaded_ = {scene_->width, scene_->height, scene_->maxDepth, scene_->integrator};
            if (moved) setView(*scene_->camera, *moved);
            film_ = Film();
        }
        return r;
    }

    /// The loaded scene's camera {eye, center, up, fovy}; its camera as loaded with `home`.
    val camera(bool home) const {
        val o = val::object();
        if (!scene_) return val::null();
        const CameraSpec& c = home ? home_ : *scene_->camera;
        o.set("eye", vecValue(c.eye));
        o.set("center", vecValue(c.center));
        o.set("up", vecValue(c.up));
        o.set("fovy", c.fovyDegrees);
        return o;
    }

    /// Moves the camera (the page's orbit, pan and zoom); the next render sees it.
    void setCamera(const val& o) {
        if (!scene_) return;
        CameraSpec& c = *scene_->camera;
        c.eye = toVec(o["eye"]);
        c.center = toVec(o["center"]);
        c.up = toVec(o["up"]);
    }

    /// Starts a render of the loaded scene with {width, height, spp, maxDepth, integrator, seed,
    /// passes, denoise}: `spp` camera rays per pixel in all (0: the scene's), in one pass, or
    /// with `passes` true, in passes of 1, 1, 2, 4, ... samples whose average the image shows as
    /// it refines (the path tracer's progressive display). With `denoise` true, the image is
    /// denoised after each pass (render passes are kept for it): the first pass shows its tiles
    /// as they come, later passes replace the whole image once they are done, so that what is
    /// shown is always a whole denoised image. Size, depth and integrator not given are the
    /// scene's as loaded (not those of the render before: a preview's). Returns {error (or
    /// null), width, height}.
    val begin(const val& o) {
        val r = val::object();
        r.set("error", val::null());
        if (!scene_) {
            r.set("error", errorValue(RenderError("no scene is loaded")));
            return r;
        }
        Scene& s = *scene_;
        s.width = std::clamp(intOr(o, "width", loaded_.width), 1, 16384);
        s.height = std::clamp(intOr(o, "height", loaded_.height), 1, 16384);
        s.maxDepth = std::max(0, intOr(o, "maxDepth", loaded_.maxDepth));
        s.integrator = loaded_.integrator;
        // No light pass (the path tracer's caustics, render/integrators/caustics.h): it traces a
        // whole pass's light paths before the pass's first tiles, longer than a step may take (the
        // page must stay responsive and cancel within a step). The camera's paths find
        // caustics alone, as `--caustics off` does.
        s.caustics = false;
        if (o["integrator"].isString()) {
            std::string name = o["integrator"].as<std::string>();
            if (!findIntegrator(name)) {
                r.set("error", errorValue(RenderError("no integrator '" + name + "'")));
                return r;
            }
            s.integrator = name;
        }
        spp_ = std::max(1, intOr(o, "spp", s.spp > 0 ? s.spp : 1));
        seed_ = static_cast<uint64_t>(std::max(0, intOr(o, "seed", 0)));
        progressive_ = o["passes"].isTrue();
        denoise_ = o["denoise"].isTrue();
        denoiser_ = o["denoiser"].isString() ? denoiserNamed(o["denoiser"].as<std::string>())
                                             : DenoiserKind::Auto;
        film_ = Film(s.width, s.height);
        sums_ = FilmSums(s.width, s.height);
        if (denoise_) sums_.keepPasses();
        rgba_.assign(static_cast<size_t>(s.width) * s.height * 4, 0);
        tilesX_ = (s.width + kTile - 1) / kTile;
        tiles_ = tilesX_ * ((s.height + kTile - 1) / kTile);
        next_ = 0;
        integrator_.reset();  // made for the scene as it is now (camera, size, integrator)
        batch_ = pool_.threads() * 2;
        pass_ = 0;
        samples_ = 0;
        rays_ = 0;
        seconds_ = 0;
        denoiseSeconds_ = 0;
        denoiseRow_ = -1;
        display_ = {0, s.display.srgb, s.display.toneMap};
        r.set("width", s.width);
        r.set("height", s.height);
        return r;
    }

    /// Renders tiles for about `milliseconds` (at least one batch of them). Returns {done, pass,
    /// samples, fraction, rays, seconds, denoiseSeconds, x0, y0, x1, y1}: the pixels changed by
    /// this call lie in [x0, x1) x [y0, y1). Throws nothing: an error is {error}.
    val step(double milliseconds) {
        val r = val::object();
        if (!scene_ || film_.width() == 0) {
            r.set("error", errorValue(RenderError("no render")));
            return r;
        }
        const Scene& s = *scene_;
        auto start = Clock::now();
        int x0 = s.width, y0 = s.height, x1 = 0, y1 = 0;
        try {
            while (samples_ < spp_ || denoiseRow_ >= 0) {
                // A finished pass is denoised a band of rows per turn, so that a large image's
                // denoising is heard between calls (Cancel) as a pass's tiles are.
                if (denoiseRow_ >= 0) {
                    denoiseBand();
                    if (denoiseRow_ < 0) x0 = y0 = 0, x1 = s.width, y1 = s.height;
                    if (std::chrono::duration<double, std::milli>(Clock::now() - start).count() >=
                        milliseconds)
                        break;
                    continue;
                }
                const int passSpp =
                    progressive_ ? std::min(spp_ - samples_, std::max(1, samples_)) : spp_;
                RenderOptions ro;
                ro.pool = &pool_;
                ro.tileSize = kTile;
                ro.spp = passSpp;
                ro.seed = passSeed(seed_, pass_);
                ro.firstTile = next_;
                ro.tileCount = batch_;
                ro.accumulate = &sums_;  // each pixel's samples of every pass, summed
                ro.aovs = denoise_;
                // One integrator for the pass's batches of tiles (making one collects the
                // scene's lights and builds their tree).
                if (!integrator_ || integratorSpp_ != passSpp) {
                    integrator_ = makeIntegrator(s, {passSpp});
                    integratorSpp_ = passSpp;
                }
                ro.integrator = integrator_.get();
                RenderResult pass = render(s, ro);
                rays_ += pass.rays.total();
                seconds_ += pass.seconds;
                // The first pass shows its tiles as they come; with the denoiser, later passes
                // show nothing until they are whole (then the whole image, denoised).
                const bool show = !denoise_ || samples_ == 0;
                for (int t = next_; t < next_ + pass.tilesTotal; ++t) {
                    int tx0 = t % tilesX_ * kTile, ty0 = t / tilesX_ * kTile;
                    int tx1 = std::min(tx0 + kTile, s.width), ty1 = std::min(ty0 + kTile, s.height);
                    resolveTile(tx0, ty0, tx1, ty1, show);
                    if (!show) continue;
                    x0 = std::min(x0, tx0), y0 = std::min(y0, ty0);
                    x1 = std::max(x1, tx1), y1 = std::max(y1, ty1);
                }
                next_ += pass.tilesTotal;
                // Batches of about 10 to 40 ms: each call wakes the threads and waits for the
                // last of them, a cost worth paying only for enough tiles.
                if (pass.seconds < 0.01 && batch_ < tiles_) batch_ *= 2;
                if (pass.seconds > 0.04 && batch_ > pool_.threads()) batch_ /= 2;
                if (next_ >= tiles_) {
                    next_ = 0;
                    ++pass_;
                    samples_ += passSpp;
                    if (denoise_) beginDenoising();
                }
                if (std::chrono::duration<double, std::milli>(Clock::now() - start).count() >=
                    milliseconds)
                    break;
            }
        } catch (const std::exception& e) {
            film_ = Film();
            r.set("error", errorValue(e));
            return r;
        }
        r.set("done", samples_ >= spp_ && denoiseRow_ < 0);
        r.set("pass", pass_);
        r.set("samples", samples_);
        r.set("fraction",
              std::min(1.0, (samples_ + double(next_) / tiles_ * nextPassSpp()) / spp_));
        r.set("rays", static_cast<double>(rays_));
        r.set("seconds", seconds_);
        r.set("denoiseSeconds", denoiseSeconds_);
        r.set("denoiser", denoisedWith_);
        r.set("x0", x0), r.set("y0", y0), r.set("x1", std::max(x0, x1)),
            r.set("y1", std::max(y0, y1));
        return r;
    }

    /// The image so far as RGBA bytes, width x height, row 0 at the top: a view of the module's
    /// memory, valid until the next call (copy it before the memory can grow).
    val image() const { return val(emscripten::typed_memory_view(rgba_.size(), rgba_.data())); }

    /// Writes the image so far to `path` (its format by extension, as -o), as the command line
    /// writes it. Returns an error message, or an empty string.
    std::string save(const std::string& path) const {
        try {
            if (film_.width() == 0) throw RenderError("nothing rendered yet");
            writeImage(path, film_, display_);
            return {};
        } catch (const std::exception& e) {
            return e.what();
        }
    }

  private:
    int nextPassSpp() const {
        return progressive_ ? std::min(spp_ - samples_, std::max(1, samples_)) : spp_;
    }

    /// The image's tile [x0, x1) x [y0, y1) from the sums of every pass so far (the rule of a
    /// one-pass render, so that one is the command line's, bit for bit), and with `show` into
    /// the RGBA bytes through the display transform.
    void resolveTile(int x0, int y0, int x1, int y1, bool show) {
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x)
                film_.at(x, y) = pixelValue(sums_.sum(x, y).value(), sums_.weight(x, y));
        if (show) showTile(film_, x0, y0, x1, y1);
    }

    /// Denoises the image of the passes so far, guided by their render passes, and shows it.
    /// Below two samples a pixel's variance is unknown: the denoiser then estimates the noise
    /// from the image.
    /// Starts denoising the image of the passes so far (denoiseBand() does it). The last
    /// pass's image goes through the network denoiser where its weights are registered
    /// (registerDenoiserWeights(); the page fetches them), whole: it is not cut into bands,
    /// so Cancel is heard after it. Earlier passes, and the last without the weights, take the
    /// non-local-means filter, a band at a time.
    void beginDenoising() {
        auto start = Clock::now();
        toDenoise_ = sums_.resolve();
        toDenoisePasses_ = sums_.resolvePasses();
        if (samples_ < 2) {
            toDenoisePasses_.variance.clear();
            toDenoisePasses_.albedoVariance.clear();
        }
        if (samples_ >= spp_ &&
            resolveDenoiser(denoiser_, DenoiseQuality::Balanced, !toDenoisePasses_.albedo.empty(),
                            !toDenoisePasses_.normal.empty()) == DenoiserKind::Oidn) {
            FilmDenoiseReport report;
            film_ = denoiseFilm(toDenoise_, toDenoisePasses_, pool_,
                                {DenoiserKind::Oidn, DenoiseQuality::Balanced}, &report);
            denoiser_ = DenoiserKind::Oidn;
            denoisedWith_ = report.method;
            showTile(film_, 0, 0, film_.width(), film_.height());
            toDenoise_ = Film();
            toDenoisePasses_ = RenderPasses();
            denoiseRow_ = -1;
            denoiseSeconds_ += std::chrono::duration<double>(Clock::now() - start).count();
            return;
        }
        denoisedWith_ = "nlm";
        denoised_ = Film(toDenoise_.width(), toDenoise_.height());
        denoiseRow_ = 0;
        denoiseSeconds_ += std::chrono::duration<double>(Clock::now() - start).count();
    }

    /// Denoises the next band of rows (about 128K pixels: a tenth of a second or two here); after
    /// the last, shows the denoised image.
    void denoiseBand() {
        auto start = Clock::now();
        const int w = toDenoise_.width(), h = toDenoise_.height();
        const int y0 = denoiseRow_, y1 = std::min(h, y0 + std::max(16, (1 << 17) / std::max(w, 1)));
        const Film band = denoiseFilmRows(toDenoise_, toDenoisePasses_, y0, y1, pool_);
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x) denoised_.at(x, y) = band.at(x, y - y0);
        denoiseRow_ = y1;
        if (y1 >= h) {
            film_ = std::move(denoised_);
            showTile(film_, 0, 0, film_.width(), film_.height());
            toDenoise_ = denoised_ = Film();
            toDenoisePasses_ = RenderPasses();
            denoiseRow_ = -1;
        }
        denoiseSeconds_ += std::chrono::duration<double>(Clock::now() - start).count();
    }

    /// Writes [x0, x1) x [y0, y1) of `film` into the RGBA bytes through the display transform.
    void showTile(const Film& film, int x0, int y0, int x1, int y1) {
        Film tile(x1 - x0, y1 - y0);
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) tile.at(x - x0, y - y0) = film.at(x, y);
        Image8 bytes = toImage8(tile, display_);
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) {
                uint8_t* p = &rgba_[(static_cast<size_t>(y) * film_.width() + x) * 4];
                for (int c = 0; c < 3; ++c) p[c] = bytes.at(x - x0, y - y0, c);
                p[3] = 255;
            }
    }

    ThreadPool pool_;
    std::unique_ptr<AssetCache> assets_ = std::make_unique<AssetCache>();  // parsed model files
    std::unique_ptr<Scene> scene_;
    std::unique_ptr<Integrator> integrator_;  // of the render begun, for its passes
    int integratorSpp_ = 0;
    CameraSpec home_;
    struct {
        int width = 0, height = 0, maxDepth = 0;
        std::string integrator;
    } loaded_;       // the loaded scene's settings, which begin() falls back on
    Film film_;      // the image so far: the average of the passes' samples (denoised)
    FilmSums sums_;  // every pass's samples summed (and their render passes, to denoise)
    std::vector<uint8_t> rgba_;
    DisplayTransform display_;
    int spp_ = 1, tiles_ = 0, tilesX_ = 0, next_ = 0, batch_ = 1, pass_ = 0, samples_ = 0;
    bool progressive_ = false, denoise_ = false;
    DenoiserKind denoiser_ = DenoiserKind::Auto;
    std::string denoisedWith_;  // the last denoise's method: "oidn balanced", "nlm"
    uint64_t seed_ = 0, rays_ = 0;
    double seconds_ = 0, denoiseSeconds_ = 0;
    // A finished pass's image being denoised a band at a time: its next row (-1: none), the
    // image and its passes, and the denoised rows so far.
    int denoiseRow_ = -1;
    Film toDenoise_, denoised_;
    RenderPasses toDenoisePasses_;
};

/// What `glint SCENE -o OUTPUT -t THREADS --kernels KERNELS` does, for the Node tests: the
/// scene's size, samples, depth and output settings. Returns an error message, or "".
std::string renderFile(const std::string& path, const std::string& output, int threads,
                       const std::string& kernels) {
    try {
        std::vector<Diagnostic> warnings;
        ModelScene m = loadSceneFile(path, warnings);
        Scene& scene = *m.scene;
        ThreadPool pool(std::max(1, threads));
        scene.prepare({&pool, Bvh::named(kernels)});
        RenderOptions ro;
        ro.pool = &pool;
        ro.spp = scene.spp > 0 ? scene.spp : 1;
        RenderResult result = render(scene, ro);
        writeImage(output, result.film, {0, scene.display.srgb, scene.display.toneMap});
        return {};
    } catch (const std::exception& e) {
        return e.what();
    }
}

/// Makes `bytes` (a Uint8Array of an OIDN weights file) the network denoiser's weights `name`
/// ("rt_hdr_alb_nrm"): the page fetches them beside itself. Returns an error message, or "".
std::string registerWeights(const std::string& name, const val& bytes) {
    try {
        // Copied in by the typed array's own set(), not element by element.
        std::vector<uint8_t> data(bytes["length"].as<size_t>());
        val(emscripten::typed_memory_view(data.size(), data.data())).call<void>("set", bytes);
        parseTza(data, name);  // refused now rather than at the first denoise
        registerDenoiserWeights(name, std::move(data));
        return {};
    } catch (const std::exception& e) {
        return e.what();
    }
}

/// The denoiser a render's last pass gets: "oidn" once the page has registered the network's
/// weights, else "nlm".
std::string denoiser() { return std::string(denoiserName(resolveDenoiser(DenoiserKind::Auto))); }

/// The default traversal kernels ("simd128"), as `glint --help` names them natively.
std::string kernels() { return Bvh::isa(); }

/// The integrators by name, for the page's menu.
val integratorNames() {
    val a = val::array();
    for (const IntegratorInfo& i : integrators()) a.call<void>("push", std::string(i.name));
    return a;
}

/// The scene format's command names, for the editor's highlighting.
val commandNames() {
    val a = val::array();
    for (std::string_view name : courseCommandNames()) a.call<void>("push", std::string(name));
    return a;
}

EMSCRIPTEN_BINDINGS(glint) {
    emscripten::class_<Session>("Session")
        .constructor<int>()
        .function("threads", &Session::threads)
        .function("load", &Session::load)
        .function("camera", &Session::camera)
        .function("setCamera", &Session::setCamera)
        .function("begin", &Session::begin)
        .function("step", &Session::step)
        .function("image", &Session::image)
        .function("save", &Session::save);
    emscripten::function("renderFile", &renderFile);
    emscripten::function("kernels", &kernels);
    emscripten::function("registerWeights", &registerWeights);
    emscripten::function("denoiser", &denoiser);
    emscripten::function("integratorNames", &integratorNames);
    emscripten::function("commandNames", &commandNames);
}

}  // namespace glint::web
