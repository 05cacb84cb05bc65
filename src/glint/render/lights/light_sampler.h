#pragma once
/// Every source of light in a scene, as a physically based integrator samples them: the point
/// and directional lights, every emissive surface (triangles, meshes, spheres and the other
/// shapes, including the geometry of quad lights) as an area light, and the environment map or
/// the background as an environment light. One is chosen per shading point, then sampled:
/// emissive surfaces uniformly by area (see geometry/surface_sampling.h), an environment map
/// by its luminance (scene/environment.h), a constant or gradient background uniformly over
/// the sphere; a triangle that is neither tiny nor huge seen from the point uniformly over the
/// solid angle it fills (Arvo 1995: math/spherical_triangle.h); a round sphere, from outside,
/// uniformly over the cone of directions it fills (pbrt-v4's Sphere::Sample), which puts every
/// sample on the side facing the point. The choice is made in two steps: the lights at infinity
/// (the environment, directional lights) against the others by what each group may give the shading
/// point (the others' light tree's importance, against the irradiance the lights at infinity give
/// in the same units), then within the group: a light at infinity by its irradiance, one of
/// the others through the light tree (render/lights/light_tree.h, pbrt-v4's BVHLightSampler), by its
/// power, distance and orientation as seen from the shading point and its normal.
///
/// Emissive planes, which are infinite, are lights at infinity beside the environment (each
/// gives a point in front of it pi L, whatever the distance), sampled by the cosine about their
/// normal over the half of the directions that meet them. Emissive triangles that instances
/// place are sampled as the scene's own, each placement a light of its own.

#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include "glint/math/distribution.h"
#include "glint/render/lights/light_tree.h"
#include "glint/scene/scene.h"

namespace glint {

/// A direction towards a light chosen and sampled by LightSampler::sample.
struct LightSample {
    Vec3 wi;  ///< Unit, from the shading point towards the light.
    Vec3 L;   ///< Radiance arriving along -wi (delta lights: intensity over attenuation).
    /// Density of wi over solid angle, times the probability of choosing the light; for delta
    /// lights, just that probability.
    double pdf = 0;
    double distance = 0;  ///< To the point on the light; infinity for distant lights.
    bool delta = false;   ///< A point or directional light: no BSDF sample can reach it.
    /// Whether the light pass (render/integrators/caustics.h) traces light from here: every light but the
    /// emissive planes, the background and the dim parts of an environment map (leftToPass()).
    bool leftToPass = false;
};

/// A ray leaving a light, for tracing light from it (render/integrators/caustics.h).
struct EmittedRay {
    Ray ray;  ///< From the light's surface, or from outside the scene for lights at infinity.
    /// Emitted radiance times |cos| at the light over the densities of the point and the
    /// direction: the flux the ray carries, in the units of a path's throughput.
    Vec3 beta;
    /// A point light with the course's attenuation: beta is still to be multiplied by
    /// d^2 / attenuation(d), d the distance to the first surface the ray meets.
    const Light* attenuated = nullptr;
};

class LightSampler {
  public:
    /// Collects the lights of the prepared `scene`, which must outlive the sampler.
    explicit LightSampler(const Scene& scene);

    bool empty() const { return lights_.empty(); }
    size_t size() const { return lights_.size(); }

    /// Chooses a light with `uLight` for point `p` whose surface normal is `n` (zero: p
    /// receives from every side, behind glass or in a medium) and samples a direction towards
    /// it with `u`. None if nothing arrives (p behind a one-sided emitter, on the light itself,
    /// ...).
    std::optional<LightSample> sample(const Vec3& p, const Vec3& n, double uLight, Point2 u) const;

    /// The density (as LightSample::pdf) with which sample() from `from` with normal `fromN`
    /// would have drawn the direction to `hit`, a point on an emissive surface that a ray from
    /// `from` reached; 0 if that surface is not among the sampled lights.
    double pdfHit(const Vec3& from, const Vec3& fromN, const Hit& hit,
                  const SurfaceInteraction& si) const;

    /// The probability with which sample() chooses light `index` (of size()) for `p`, `n`.
    double choiceProbability(size_t index, const Vec3& p, const Vec3& n) const;

    /// The density (as LightSample::pdf) with which sample() from `from` with normal `fromN`
    /// draws the direction `dir` towards the environment; 0 if the background is black.
    double pdfEnvironment(const Vec3& dir, const Vec3& from, const Vec3& fromN) const;

    /// Radiance of the environment (the map, else the background) arriving from direction `dir`.
    Vec3 environment(const Vec3& dir) const { return scene_.backgroundRadiance(dir); }

    /// environment(dir) and pdfEnvironment(dir, from, fromN) together, the map looked up once.
    Vec3 environment(const Vec3& dir, const Vec3& from, const Vec3& fromN, double* pdf) const;

    /// Whether the light pass traces the light of an environment map's direction of radiance
    /// `radiance`: where the map is much brighter than its mean (the sun, lamps in the map), a
    /// small light that paths through glass hardly find; the rest of the sky, like the emissive
    /// planes and the plain background, is large, and the camera's paths find it well.
    bool environmentLeftToPass(const Vec3& radiance) const {
        return luminance(radiance) > passThreshold_;
    }

    /// For tracing light into the sphere of centre `center` and radius `radius` (a part of the
    /// scene that holds everything of interest): a weight for each light, about the power it
    /// sends into the sphere.
    std::vector<double> emissionWeights(const Vec3& center, double radius) const;
    /// A ray from light `index` into that sphere: from a point drawn uniformly by area (`uPoint`)
    /// in a direction drawn uniformly over the cone of directions the sphere fills from there
    /// (`uDir`; over every direction from inside it); from a light at infinity (a direction
    /// drawn as sample() draws it), across the sphere's disc seen from that direction, from
    /// `far` beyond its centre. None if the light sends nothing that way.
    std::optional<EmittedRay> emit(size_t index, const Vec3& center, double radius, double far,
                                   Point2 uPoint, Point2 uDir) const;

  private:
    enum class Kind : uint8_t { Point, Directional, Triangle, Sphere, Shape, Plane, Environment };
    struct Entry {
        Kind kind;
        uint32_t index;          ///< Into scene.lights, or a primitive id.
        bool frontOnly = false;  ///< Triangles of quad lights emit from their front face only.
        double pdfArea = 0;      ///< Triangles: 1 / area.
        Vec3 emission{};         ///< Emissive surfaces: their radiance (textured: the mean).
        /// Triangles with an emissive texture: their physically based material's id.
        uint32_t texturedPbr = 0;
        /// Triangles an instance places (`index` the instance): the triangle of its mesh;
        /// UINT32_MAX for the scene's own.
        uint32_t sub = UINT32_MAX;
        /// Triangles: the corner c, the edges a - c and b - c, and the unit normal of
        /// cross(b - a, c - a): a point is c + (a - c) b0 + (b - c) b1. Planes: a point c on
        /// it and its unit normal n.
        Vec3 c{}, ca{}, cb{}, n{};
        /// Spheres placed by a similarity (a round sphere in the world): its world centre and
        /// radius, and it is sampled by its cone of directions from outside; radius 0: by area.
        Vec3 center{};
        double radius = 0;
        /// Lights at infinity: the weight they are chosen by among themselves and against the
        /// tree (the irradiance they give, in the tree's units).
        double weight = 0;
        double power = 0;  ///< Bounded lights: the power the light tree weighs them by,
        Vec3 middle{};     ///< and the middle of their bounds.
    };
    std::optional<LightSample> sampleEntry(const Entry& e, const Vec3& p, Point2 u) const;
    /// The emission of textured triangle `e` at barycentrics (b1, b2) of its b and c corners.
    Vec3 texturedEmission(const Entry& e, double b1, double b2) const;
    /// Triangle `e` seen from `p`: the unit directions to its corners, and the solid angle
    /// it fills where it is sampled by solid angle (neither tiny nor nearly a hemisphere); 0
    /// where it is sampled by area.
    struct SphericalTriangle {
        Vec3 a, b, c;
        double solidAngle = 0;
    };
    static SphericalTriangle sphericalTriangle(const Entry& e, const Vec3& p);
    /// A direction uniformly within that solid angle.
    std::optional<LightSample> sampleTriangleSolidAngle(const Entry& e, const Vec3& p, Point2 u,
                                                        const SphericalTriangle& t) const;
    /// A round sphere's cone sample from `p` outside it; none from inside or if not round.
    std::optional<LightSample> sampleSphereCone(const Entry& e, const Vec3& p, Point2 u) const;

    const Scene& scene_;
    std::vector<Entry> lights_;
    /// Sets passThreshold_ and passShare_ for the environment map.
    void passShareOfMap(const EnvironmentMap& map);
    /// The probability of choosing one of the lights at infinity at `p`, `n`.
    double pInfinite(const Vec3& p, const Vec3& n) const;

    /// The lights at infinity, by index, and their weights' sum; the others are in the tree.
    std::vector<uint32_t> infinite_;
    double infiniteTotal_ = 0;
    LightTree tree_;
    std::vector<uint32_t> lightOfTreeLeaf_;  ///< Tree light k is lights_[lightOfTreeLeaf_[k]].
    std::vector<uint32_t> treeLeafOf_;       ///< And back (UINT32_MAX: at infinity).
    /// Light index of each bounded primitive (none: UINT32_MAX); empty if no surface emits.
    std::vector<uint32_t> lightOfPrimitive_;
    /// Light index of each emissive triangle instances place, by (instance id << 32 | its
    /// triangle in the mesh).
    std::unordered_map<uint64_t, uint32_t> lightOfInstanced_;
    uint32_t environment_ = UINT32_MAX;  ///< Index of the environment light, if any.
    /// environmentLeftToPass's luminance (infinite without a map), and the share of the map's
    /// power above it.
    double passThreshold_ = kInfinity, passShare_ = 0;
};

}  // namespace glint
