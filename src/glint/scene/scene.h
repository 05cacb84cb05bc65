#pragma once
/// Everything needed to render: settings, camera, lights, materials and geometry.

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "glint/accel/bvh.h"
#include "glint/geometry/primitives.h"
#include "glint/scene/camera.h"
#include "glint/scene/display_spec.h"
#include "glint/scene/environment.h"
#include "glint/scene/filter_spec.h"
#include "glint/scene/light_spec.h"
#include "glint/scene/material.h"
#include "glint/scene/medium.h"
#include "glint/scene/pbr_material.h"
#include "glint/scene/texture.h"

namespace glint {

/// Colour of rays that hit nothing: constant, or a vertical gradient from `down` (looking
/// straight down) to `up` (looking straight up), linear in the direction's y component.
struct Background {
    Vec3 down, up;

    Vec3 eval(const Vec3& dir) const {
        double t = (dir.y + 1) * 0.5;
        return down * (1 - t) + up * t;
    }
};

/// A shadow catcher (the ground of a framed model, docs/cli.md "Rendering a model"): the
/// infinite horizontal plane y = height, seen from above and only by camera rays and the rays
/// mirrors and glass continue from them. Where they meet it, it shows what lies behind it (the
/// environment or the background) darkened by the shadows the scene casts on it; every other
/// ray passes through it, so it adds no light and no occlusion. Rendered by the path tracer
/// (render/integrators/shadow_catcher.h); the Whitted integrator ignores it.
struct ShadowCatcher {
    double height = 0;
};

/// Limits on what a scene may ask for, checked by loaders before anything is allocated.
constexpr int kMaxImageSide = 32768;
constexpr long long kMaxImagePixels = 1LL << 27;
constexpr int kMaxDepthLimit = 64;
/// Geometry is searched in float: world coordinates beyond this, or spheres whose smallest
/// semi-axis is below its inverse, would overflow the intersection arithmetic.
constexpr double kMaxCoordinate = 1e18;

/// Whether `p` lies within the supported coordinate range (kMaxCoordinate on every axis).
inline bool withinCoordinateRange(const Vec3& p) {
    return std::abs(p.x) <= kMaxCoordinate && std::abs(p.y) <= kMaxCoordinate &&
           std::abs(p.z) <= kMaxCoordinate;
}

/// The acceleration structures of one frame of a sequence, kept for the next (Scene::keepAccel,
/// PrepareOptions::reuse): where the next frame's primitives are the same ones moved, as when
/// an animation plays, Scene::prepare refits them (Bvh::refit) instead of building anew.
struct FrameAccel {
    Bvh scene;
    std::vector<Bvh> meshes;  ///< The shared meshes', in their order.
    bool kept = false;        ///< Whether a frame's are here.
};

/// The path tracer's bounce limits by kind (`--max-bounces`, Cycles' Light Paths): a path
/// ends after its n-th bounce of a kind whose limit is n, as it does after Scene::maxDepth
/// bounces in all. Transmission is a BSDF sample through the surface, diffuse and glossy are
/// reflections (glossy includes mirrors), volume a scattering in a medium. Unlimited by
/// default; the model mode lets glass go deeper than the rest.
struct BounceLimits {
    static constexpr int kUnlimited = 1 << 30;
    int diffuse = kUnlimited, glossy = kUnlimited, transmission = kUnlimited, volume = kUnlimited;
    bool operator==(const BounceLimits&) const = default;
};

/// How Scene::prepare builds the acceleration structures.
struct PrepareOptions {
    /// The threads to build on, the calling thread among them; null: all hardware threads.
    ThreadPool* pool = nullptr;
    Isa kernels = Isa::Auto;  ///< Traversal kernels; Auto: the best this CPU runs.
    /// The last frame's structures, to refit where they fit; taken (left empty) either way.
    FrameAccel* reuse = nullptr;
    /// A refitted tree is kept while its summed box areas (Bvh::relativeArea) stay within this
    /// factor of those it was built with; past it, it is built anew.
    double refitGrowth = 1.25;
};

/// A scene is built in place (geometry is referenced by its BVH), so it is neither copied
/// nor moved: loaders hand it out in a unique_ptr.
class Scene {
  public:
    Scene() = default;
    Scene(const Scene&) = delete;
    Scene& operator=(const Scene&) = delete;

    int width = 640, height = 480;
    int maxDepth = 5;      ///< Primary rays are depth 0; reflect while depth < maxDepth.
    BounceLimits bounces;  ///< The path tracer's limits by kind, within maxDepth.
    /// The path tracer's clamp of indirect light (`--clamp-indirect`, Cycles' "Clamp
    /// Indirect"): each sample's light that reached the camera after two or more bounces is
    /// scaled down to at most this in its largest channel. 0: no clamp (unbiased).
    double clampIndirect = 0;
    /// Whether the path tracer traces caustics from the lights (`--caustics`,
    /// render/integrators/caustics.h).
    bool caustics = true;
    /// The integrator that renders the scene, by name (render/integrators/integrator.h;
    /// `integrator`).
    std::string integrator = "whitted";
    std::string output;  ///< Output file the scene asks for; may be empty.
    std::optional<CameraSpec> camera;
    /// A moving camera: its specs at evenly spaced times over the shutter, from its opening to
    /// its closing (the first is `camera`); empty for a still one (docs/animation.md).
    std::vector<CameraSpec> cameraMotion;
    /// Whether anything moves over the shutter: the camera or a primitive. Each camera sample
    /// of such a scene then has its own time (math/motion.h).
    bool moves() const { return cameraMotion.size() > 1 || primitives.hasMotion(); }
    Background background;  ///< Black by default, as the course expects.
    /// An environment map (`environment`): radiance from every direction at infinity, in place
    /// of the background. Null: none.
    std::shared_ptr<const EnvironmentMap> environment;
    /// A ground that shows shadows only; none by default.
    std::optional<ShadowCatcher> shadowCatcher;
    /// How the image is meant to be shown: the course's clamp by default (the command line may
    /// override it).
    DisplaySpec display;
    std::vector<LightSpec> lights;
    /// Camera rays per pixel the scene asks for (`spp`); 0: not given (the CLI decides).
    int spp = 0;
    FilterSpec filter;  ///< Reconstruction filter (`filter`); the one-pixel box by default.
    /// Area lights are sampled with an n x n jittered grid per shading point (`lightsamples`);
    /// 0: not given (see areaLightGrid()).
    int lightSamples = 0;
    std::vector<Material> materials;
    /// Textures named by Material::texture: id k is textures[k - 1].
    std::vector<Texture> textures;
    /// Physically based materials named by Material::pbr: id k is pbrMaterials[k - 1].
    std::vector<PbrMaterial> pbrMaterials;
    /// Participating media named by Material::interior and `fog`: id k is media[k - 1].
    std::vector<Medium> media;
    /// The medium filling the scene outside every closed surface with an interior (the
    /// camera's too); 0: none (vacuum).
    uint32_t fog = 0;
    Primitives primitives;

    /// Bytes a scene of this many triangles, spheres and other shapes (boxes, cylinders,
    /// cones, disks, planes) needs at most once prepared: the primitives, the BVH (allowing
    /// for partly filled leaf blocks) and the build's temporary arrays. `normals` of the
    /// triangles carry shading normals. Loaders compare it with the memory available before
    /// allocating anything. `uvs` of the triangles carry texture coordinates.
    static size_t estimateBytes(size_t triangles, size_t spheres, size_t shapes = 0,
                                size_t normals = 0, size_t uvs = 0);

    /// Radiance arriving along a ray that hits nothing, from unit direction `dir`: the
    /// environment map's when there is one, else the background's.
    Vec3 backgroundRadiance(const Vec3& dir) const {
        if (environment) [[unlikely]]
            return environment->eval(dir);
        return background.eval(dir);
    }

    /// Id of `m`, reusing the last material when it is equal (materials change rarely).
    uint32_t addMaterial(const Material& m);
    /// Id (from 1) of a new texture for Material::texture.
    uint32_t addTexture(Texture t) {
        textures.push_back(std::move(t));
        return static_cast<uint32_t>(textures.size());
    }
    /// Id (from 1) of a new physically based material for Material::pbr.
    uint32_t addPbrMaterial(PbrMaterial m) {
        pbrMaterials.push_back(std::move(m));
        return static_cast<uint32_t>(pbrMaterials.size());
    }
    const PbrMaterial& pbr(uint32_t id) const { return pbrMaterials[id - 1]; }
    /// Id (from 1) of a new medium.
    uint32_t addMedium(Medium m) {
        media.push_back(std::move(m));
        return static_cast<uint32_t>(media.size());
    }
    const Medium& medium(uint32_t id) const { return media[id - 1]; }
    /// The texture of id `id` (1 to textures.size()).
    const Texture& texture(uint32_t id) const { return textures[id - 1]; }

    /// Stores `mesh` (triangles in their own space) once, for instances to place
    /// (primitives.addInstance). Returns its index there.
    uint32_t addSharedMesh(Primitives mesh);
    /// Triangles stored in shared meshes, each counted once.
    size_t sharedTriangleCount() const;

    /// Builds the acceleration structures (the shared meshes', then the scene's over its
    /// primitives and instances) and derived settings. Call once geometry is final.
    void prepare(const PrepareOptions& options = {});
    /// Hands the acceleration structures to the next frame of a sequence (`into`); the scene
    /// is no longer prepared.
    void keepAccel(FrameAccel& into);
    bool prepared() const { return prepared_; }

    const Bvh& bvh() const { return bvh_; }

    /// The closest hit along `ray` that is not cut out: texels of alpha-masked materials below
    /// their cutoff and, with probability 1 - alpha, texels of alpha-blended ones are passed
    /// through, and so are back faces of single-sided materials (glTF's back-face culling) and
    /// surfaces hidden from the camera for `camera` rays. Integrators search the scene through this
    /// and occluded().
    bool intersect(const Ray& ray, Hit& hit, bool cameraRay = false) const {
        if (!bvh_.intersect(ray, hit)) return false;
        if (!cutouts_ && !(cameraRay && filtersCamera_)) [[likely]]
            return true;
        return filterHit(ray, hit, cameraRay);
    }
    /// Whether anything that is not cut out lies along `ray` (within its range).
    bool occluded(const Ray& ray) const {
        if (!cutouts_) [[likely]]
            return bvh_.occluded(ray);
        Hit hit;
        return intersect(ray, hit);
    }
    /// Whether camera hits must go through filterHit(): some material cuts out or culls.
    bool filtersCameraHits() const { return cutouts_ || filtersCamera_; }
    /// Given `hit`, the closest hit along `ray`, moves it to the closest one not cut out;
    /// false if none is left.
    bool filterHit(const Ray& ray, Hit& hit, bool cameraRay) const;
    /// Absolute part of the secondary-ray offset for this scene (see core/spawn.h).
    double spawnOffset() const { return spawnOffset_; }

    /// Bytes of the shared meshes' BVHs (prepared scenes only).
    size_t sharedBvhBytes() const;

  private:
    struct SharedMesh {
        Primitives primitives;  // where primitives.sharedMesh() points: SharedMesh never moves
        Bvh bvh;
    };
    std::vector<std::unique_ptr<SharedMesh>> sharedMeshes_;
    /// Whether the hit of `ray` is cut out (see intersect()).
    bool cutOut(const Ray& ray, const Hit& hit, bool cameraRay) const;
    static constexpr int kMaxCutoutLayers = 1024;

    Bvh bvh_;
    double spawnOffset_ = 0;
    bool cutouts_ = false;  ///< Some material is alpha-masked or blended.
    /// Some physically based material is single-sided or hidden from the camera: camera rays
    /// (only) are filtered; shadow and other rays keep the fast search.
    bool filtersCamera_ = false;
    bool prepared_ = false;
};

}  // namespace glint
