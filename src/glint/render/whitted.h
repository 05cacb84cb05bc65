#pragma once
/// The course's recursive (Whitted) ray tracer: OpenGL-style local lighting with shadow rays,
/// plus one mirror ray weighted by the specular colour, to the scene's maximum depth.

#include <cstdint>

#include "glint/scene/scene.h"

namespace glint {

/// Rays traced, by kind.
struct RayCounts {
    uint64_t camera = 0, shadow = 0, reflection = 0;

    uint64_t total() const { return camera + shadow + reflection; }
    RayCounts& operator+=(const RayCounts& o) {
        camera += o.camera;
        shadow += o.shadow;
        reflection += o.reflection;
        return *this;
    }
};

class WhittedIntegrator {
  public:
    /// The scene must be prepared and outlive the integrator.
    explicit WhittedIntegrator(const Scene& scene) : scene_(scene) {}

    /// Radiance along `ray`, which is at recursion `depth` (0 for camera rays). Counts the
    /// rays it traces into `counts`, `ray` itself included.
    Vec3 li(const Ray& ray, int depth, RayCounts& counts) const;

    /// Radiance along `ray` given its closest hit (null: it hits nothing), found by the caller,
    /// e.g. for a whole packet at once. Does not count `ray` itself.
    Vec3 shade(const Ray& ray, const Hit* hit, int depth, RayCounts& counts) const;

  private:
    const Scene& scene_;
};

}  // namespace glint
