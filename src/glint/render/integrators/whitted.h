#pragma once
/// The course's recursive (Whitted) ray tracer: OpenGL-style local lighting with shadow rays,
/// plus one mirror ray weighted by the specular colour, to the scene's maximum depth; and
/// Glint's extensions of it, following the lecture: refraction with Fresnel weighting, soft
/// shadows from area lights, and a rough (GGX) specular lobe. See docs/scene-format.md.

#include <vector>

#include "glint/render/integrators/integrator.h"
#include "glint/render/lights/light.h"

namespace glint {

/// n of the n x n grid of shadow rays per area light and shading point: the scene's
/// `lightsamples`, else about 16 shadow rays per pixel spread over the pixel's samples.
int areaLightGrid(const Scene& scene, int spp);

class WhittedIntegrator final : public Integrator {
  public:
    /// The scene must be prepared and outlive the integrator. `spp` is the number of camera
    /// samples per pixel (it sets the default area-light grid).
    explicit WhittedIntegrator(const Scene& scene, int spp = 1);

    /// Radiance along `ray`, which is at recursion `depth` (0 for camera rays), tracing it
    /// alone. Counts the rays it traces into `counts`, `ray` itself included.
    Vec3 radiance(const Ray& ray, int depth, RayCounts& counts) const {
        PathContext ctx{Rng(), counts};
        return trace(ray, depth, 1, ctx);
    }

    /// Integrator: radiance along the camera ray `ray` given its closest hit (null: none).
    Vec3 li(const Ray& ray, const Hit* hit, PathContext& ctx) const override;

    /// The fraction of light that travels from `p` along unit `wi` for `distance`: 0 or 1
    /// past opaque surfaces; through transmissive ones, the product over the surfaces crossed
    /// of transmission x (1 - Fresnel reflectance), 0 at total internal reflection.
    Vec3 transmittance(const Vec3& p, const Vec3& wi, double distance, RayCounts& counts) const;

    /// Whether shading draws random numbers (area lights, rough materials); if not, paths
    /// need no seeded PathContext::rng.
    bool usesRandomNumbers() const override { return usesRandomNumbers_; }

  private:
    Vec3 trace(const Ray& ray, int depth, double weight, PathContext& ctx) const;
    /// `weight`: the largest channel of the product of ray weights down to this ray, for
    /// cutting off negligible branches at transmissive surfaces.
    Vec3 shade(const Ray& ray, const Hit* hit, int depth, double weight, PathContext& ctx) const;
    /// shade() for a hit. Out of line, so that the miss path (the background or the
    /// environment map) stays inline in the callers whatever it costs to look up.
    [[gnu::noinline]] Vec3 shadeSurface(const Ray& ray, const Hit& hit, int depth, double weight,
                                        PathContext& ctx) const;
    /// shade() for a hit `si` on material `m`, both known; `frontOnly`: m emits from the
    /// front face only. Lights are gathered with `lit`: `si` itself, or `si` with its normals
    /// turned towards the viewer (the back face of a double-sided glTF material).
    Vec3 shadeHit(const Ray& ray, const SurfaceInteraction& si, const SurfaceInteraction& lit,
                  const Material& m, bool frontOnly, int depth, double weight,
                  PathContext& ctx) const;
    /// shadeHit() for materials with a texture (its value at the hit replaces the diffuse
    /// colour), with front-only emission, or physically based (a double-sided one is lit on its
    /// back face as on its front): out of line, so that the course's materials pay one test
    /// for all.
    [[gnu::noinline]] Vec3 shadeSpecial(const Ray& ray, const SurfaceInteraction& si,
                                        const Material& m, int depth, double weight,
                                        PathContext& ctx) const;
    /// Adds every light's contribution at the hit to `color`. `glossyRay`: indirect() will
    /// trace the GGX lobe's reflected ray, whose finding of area lights is weighed against
    /// theirs by multiple importance sampling.
    void directLight(const SurfaceInteraction& si, const Vec3& wo, const Material& m,
                     bool glossyRay, Vec3& color, PathContext& ctx) const;
    /// directLight() for one area light: out of line, so that the point and directional
    /// lights' loop stays lean.
    [[gnu::noinline]] void areaLight(const Light& light, const SurfaceInteraction& si,
                                     const Vec3& wo, const Material& m, bool glossyRay, Vec3& color,
                                     PathContext& ctx) const;
    /// Refraction (with its Fresnel-weighted reflection) or the GGX lobe's reflected ray at a
    /// hit, recursively traced. The course's mirror ray is traced inline by shade().
    Vec3 indirect(const Ray& ray, const SurfaceInteraction& si, const Material& m, int depth,
                  double weight, PathContext& ctx) const;

    const Scene& scene_;
    std::vector<Light> lights_;  ///< The scene's own (point, spot, directional, quad).
    bool anyTransmissive_ = false;
    bool anyAreaLights_ = false;
    bool usesRandomNumbers_ = false;
    int areaGrid_ = 1;
};

}  // namespace glint
