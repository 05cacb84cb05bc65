#pragma once
/// A bounding volume hierarchy over lights (a "light tree": Conty Estevez and Kulla 2018, as
/// pbrt-v4's BVHLightSampler and Cycles 3.5 use one): each node bounds its lights' positions,
/// power and emission directions, so that a shading point can tell how much a whole group of
/// lights may give it (by distance, by which way they face, by which way it faces) and walk
/// down to one light, choosing each child in proportion to that. With many lights each shading
/// point then mostly samples the ones that matter there, where choosing by power alone sends
/// most shadow rays to lights that are far or facing away.
///
/// The tree chooses; the caller samples a point on the light chosen. The probability of a
/// light, pmf(), is what sample() returned with it, computed again along the light's path from
/// the root, so that multiple importance sampling weights a light found by a BSDF ray exactly.

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <vector>

#include "glint/math/vec3.h"

namespace glint {

/// What a light (or a group of them) may send: its positions' bounds, its power, and the cone
/// of its emission: normals within theta_o of the axis w, each emitting within theta_e of its
/// normal (pbrt-v4's LightBounds).
struct LightBounds {
    Vec3 lo{0}, hi{0};
    double phi = 0;        ///< Power (or an estimate in proportion to it), > 0.
    Vec3 w{0, 0, 1};       ///< Unit axis of the normals' cone.
    double cosThetaO = 1;  ///< Half-angle of the normals' cone; -1: any normal.
    double cosThetaE = 0;  ///< Spread of emission about a normal: 0 for a Lambertian emitter.
    bool twoSided = false;

    /// A point light at `p` of power `phi`: it emits every way.
    static LightBounds point(const Vec3& p, double phi);
    /// A surface within [lo, hi] of power `phi` emitting about normal `n` (front side only
    /// unless twoSided), or about any normal if `n` is zero (a sphere).
    static LightBounds surface(const Vec3& lo, const Vec3& hi, double phi, const Vec3& n,
                               bool twoSided);

    /// How much these lights may give point `p` whose surface normal is `n` (zero: a point
    /// that receives from every side, as in a medium or behind glass): power over squared
    /// distance, times bounds on the cosines at the light and at `p` over every point and
    /// direction the bounds allow. 0 only where none of the lights can reach p.
    double importance(const Vec3& p, const Vec3& n) const;
};

/// "LightBounds{[(lo) .. (hi)], phi 12, normals within acos(1) of (0, 0, 1), emitting within
/// acos(0), two-sided}".
std::ostream& operator<<(std::ostream& out, const LightBounds& b);

/// The bounds of two groups of lights together.
LightBounds unite(const LightBounds& a, const LightBounds& b);

class LightTree {
  public:
    LightTree() = default;
    /// Builds the tree over `lights` (each phi > 0), which it identifies by their indices.
    explicit LightTree(const std::vector<LightBounds>& lights);

    bool empty() const { return nodes_.empty(); }
    /// LightBounds::importance of all the lights together; 0 if there are none.
    double importance(const Vec3& p, const Vec3& n) const {
        return nodes_.empty() ? 0 : nodes_[0].bounds.importance(p, n);
    }

    struct Choice {
        uint32_t light;
        double probability;
    };
    /// A light for point `p` with normal `n` (see LightBounds::importance), chosen with
    /// `u` in [0, 1); none if no light can reach p.
    std::optional<Choice> sample(const Vec3& p, const Vec3& n, double u) const;
    /// The probability with which sample(p, n, u) chooses `light` over u.
    double pmf(const Vec3& p, const Vec3& n, uint32_t light) const;

  private:
    /// A node's bounds as importance() reads them, what it would compute on each call done
    /// once: the centre and radius of the box's bounding sphere, the cone's sine. In single
    /// precision, which a choice among lights needs no more than (importance() is most of
    /// the time a many-light scene spends choosing): a float square root or division costs
    /// half a double's.
    struct Compact {
        Vec3f center, w;
        float radius = 0, phi = 0, cosThetaO = 1, sinThetaO = 0, cosThetaE = 0;
        bool twoSided = false;

        explicit Compact(const LightBounds& b);
        Compact() = default;
        double importance(const Vec3& p, const Vec3& n) const;
    };
    friend struct LightBounds;

    struct Node {
        Compact bounds;
        uint32_t secondOrLight = 0;  ///< Interior: the second child's index (the first follows
                                     ///< the node); leaf: the light.
        bool leaf = false;
    };
    /// Builds the subtree over lights[begin, end) of `order`, whose path from the root is
    /// `trail` (bit d: the second child at depth d); returns its root's index, and its lights'
    /// bounds in `bounds`.
    uint32_t build(const std::vector<LightBounds>& lights, const std::vector<Vec3>& centroids,
                   std::vector<uint32_t>& order, size_t begin, size_t end, int depth,
                   uint64_t trail, LightBounds& bounds);

    std::vector<Node> nodes_;
    std::vector<uint64_t> trail_;  ///< Of each light: its path from the root.
};

}  // namespace glint
