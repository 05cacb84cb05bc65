#pragma once
/// Lights, as physically based integrators and the Whitted integrator sample them: one `Light`
/// type holding one of a few small value structs, each in a file of its own in this folder,
/// dispatched through a std::variant without allocation or virtual calls (lajolla's style, as
/// render/bsdfs/bsdf.h's BSDFs). Every source of light is one: the scene's point, spot,
/// directional and quad lights (lightFromSpec), its emissive triangles, spheres, shapes and
/// planes, and the environment. The light sampler (light_sampler.h) only chooses among them.
///
/// Conventions (pbrt-v4's). World space; directions are unit vectors.
///  - sampleLi(p, u) draws a direction wi from point p towards the light with `u` in [0, 1)^2:
///    the radiance arriving along -wi, its density over solid angle and the distance to the
///    light (LightLiSample). Delta lights (point, spot, directional) give the only direction
///    there is, with pdf 1 by convention, and pdfLi 0: no other sample can reach them.
///  - pdfLi(from, at, choice) is choice times the density with which sampleLi(from, u) draws
///    the direction to `at`, a point of the light a ray from `from` found (LightPoint; lights
///    at infinity read its direction only). `choice` (the sampler's probability of having
///    chosen the light) is multiplied in first, so the product rounds as one expression.
///  - sampleLe(uPos, uDir, ctx) draws a ray leaving the light for a light path, aimed at the
///    sphere of ctx (LightLeSample: the ray, the radiance it carries, its flux weight and the
///    densities of its origin and direction); pdfLe(p, n, dir, ctx) gives those densities for
///    any such ray, leaving point p of the light, of normal n there (delta densities 0).
///  - bounds() is what the light tree weighs a bounded light by (light_tree.h); lights at
///    infinity have none and give infiniteImportance() instead.
///
/// The Whitted integrator uses the scene's own lights (point, spot, directional, quad); the
/// path tracer every light but the quads, whose emissive triangles stand for them.

#include <iosfwd>
#include <optional>
#include <type_traits>
#include <utility>
#include <variant>

#include "glint/render/lights/directional_light.h"
#include "glint/render/lights/environment_light.h"
#include "glint/render/lights/light_sample.h"
#include "glint/render/lights/light_tree.h"
#include "glint/render/lights/plane_light.h"
#include "glint/render/lights/point_light.h"
#include "glint/render/lights/quad_light.h"
#include "glint/render/lights/shape_light.h"
#include "glint/render/lights/sphere_light.h"
#include "glint/render/lights/spot_light.h"
#include "glint/render/lights/triangle_light.h"
#include "glint/scene/light_spec.h"

namespace glint {

/// A light: one of the structs of the variant below.
///
/// A new light is a struct in a file of its own here (NAME.h, NAME.cpp), added to `Variant`;
/// the light sampler collects it (light_sampler.cpp: from the scene's LightSpecs through
/// lightFromSpec, or from the geometry or environment it stands for), and the Whitted
/// integrator lights with it if it is one of the scene's own. It must provide, or the variant
/// does not compile:
///  - sampleLi, pdfLi, sampleLe, pdfLe with the conventions above;
///  - `std::optional<LightBounds> bounds()`: its positions, power and emission cone (none for
///    a light at infinity), and `double infiniteImportance()`: for a light at infinity, pi
///    times the irradiance it gives a surface facing it (0 for bounded lights);
///  - `double lightPassShare()` and `bool tracedByLightPass(L)`: the share of its power the
///    light pass (render/integrators/caustics.h) traces, and whether it traces light of
///    radiance L from it; small lights are the pass's, large ones (planes, the sky) the camera
///    paths';
///  - `bool isDelta()`: a single direction reaches each point;
///  - `operator<<` (its parameters, for messages and failing tests), and tests of sampleLi
///    against pdfLi and of sampleLe against pdfLe in tests/unit/render/lights/.
class Light {
  public:
    using Variant = std::variant<PointLight, SpotLight, DirectionalLight, QuadLight, TriangleLight,
                                 SphereLight, ShapeLight, PlaneLight, EnvironmentLight>;

  private:
    /// f(the struct), dispatched by a chain of tests of the variant's index that inlines into
    /// the caller (std::visit's table of calls did not, and cost the Whitted integrator's light
    /// loop 2% of its instructions): the scene's own lights come first.
    template <size_t I = 0, typename F>
    [[gnu::always_inline]] auto visit(F&& f) const -> std::invoke_result_t<F, const PointLight&> {
        if constexpr (I + 1 == std::variant_size_v<Variant>) {
            return f(*std::get_if<I>(&light_));
        } else {
            if (light_.index() == I) return f(*std::get_if<I>(&light_));
            return visit<I + 1>(std::forward<F>(f));
        }
    }

  public:
    /// The light of one struct.
    template <typename L>
    requires std::is_constructible_v<Variant, L> Light(L light) : light_(std::move(light)) {}

    /// Inlined into its caller: the Whitted integrator's light loop and the light sampler.
    [[gnu::always_inline]] std::optional<LightLiSample> sampleLi(const Vec3& p, Point2 u) const {
        return visit([&](const auto& l) { return l.sampleLi(p, u); });
    }
    double pdfLi(const Vec3& from, const LightPoint& at, double choice = 1) const {
        return visit([&](const auto& l) { return l.pdfLi(from, at, choice); });
    }
    std::optional<LightLeSample> sampleLe(Point2 uPos, Point2 uDir,
                                          const LightLeContext& ctx) const {
        return visit([&](const auto& l) { return l.sampleLe(uPos, uDir, ctx); });
    }
    LightLePdf pdfLe(const Vec3& origin, const Vec3& n, const Vec3& dir,
                     const LightLeContext& ctx) const {
        return visit([&](const auto& l) { return l.pdfLe(origin, n, dir, ctx); });
    }
    std::optional<LightBounds> bounds() const {
        return visit([](const auto& l) { return l.bounds(); });
    }
    double infiniteImportance() const {
        return visit([](const auto& l) { return l.infiniteImportance(); });
    }
    double lightPassShare() const {
        return visit([](const auto& l) { return l.lightPassShare(); });
    }
    bool tracedByLightPass(const Vec3& L) const {
        return visit([&](const auto& l) { return l.tracedByLightPass(L); });
    }
    [[gnu::always_inline]] bool isDelta() const {
        return visit([](const auto& l) { return l.isDelta(); });
    }

    /// The struct, if it is an `L`: for tests, and for the sampler's environment look-ups.
    template <typename L>
    const L* as() const {
        return std::get_if<L>(&light_);
    }

    /// "PointLight{at (x, y, z), ...}": its struct's parameters.
    friend std::ostream& operator<<(std::ostream& out, const Light& light);

  private:
    Variant light_;
};

/// The light a scene declares with `spec`.
Light lightFromSpec(const LightSpec& spec);

}  // namespace glint
