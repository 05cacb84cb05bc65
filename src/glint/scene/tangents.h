#pragma once
/// Tangents for normal maps, generated the way MikkTSpace defines them (M. Mikkelsen,
/// "Simulation of wrinkled surfaces revisited", 2008; the convention of Blender, of glTF's
/// exporters and viewers, and of the baking tools that make normal maps), so that a normal map
/// baked against MikkTSpace tangents is read back with the same frame. glTF asks for them when
/// a primitive has a normal texture and no TANGENT; OBJ files never have tangents.
///
/// The algorithm, for the triangles asked for:
///  1. each triangle's tangent is dp/du and its bitangent dp/dv, from its edges and their
///     texture-coordinate differences; its handedness is the sign of its area in (u, v)
///     (+1 when the texture is not mirrored on it: dp/dv then lies along N x T);
///  2. corners with the same position, normal and texture coordinates (by value, not by index)
///     are one vertex;
///  3. at each vertex, the triangles around it that share an edge and have the same handedness
///     form a group: a vertex where the texture is mirrored across it (a uv fold) gets two
///     tangents, of opposite signs;
///  4. a group's tangent is the sum of its triangles' tangents, each projected onto the plane
///     of the vertex normal, normalised, and weighted by the triangle's angle at the vertex (the
///     angle between its edges projected onto that plane); the sum is normalised again. Its sign
///     (the `w` of MeshData::tangents) is the group's handedness.
/// Triangles whose texture coordinates have no area (degenerate uvs) take the handedness of a
/// neighbour and add nothing to the sums; a vertex whose group has no usable tangent gets a unit
/// vector orthogonal to its normal instead (never NaN). Triangles with two equal corners take the
/// tangent of another group at the same vertex. Triangles without vertex normals use their face
/// normal, as glTF's flat shading does.

#include <cstddef>
#include <cstdint>
#include <functional>

#include "glint/scene/mesh.h"

namespace glint {

/// Which triangles of a mesh generateTangents() gives tangents, and from which coordinates.
struct TangentRequest {
    /// Triangles [first, last) of MeshData::triangles (clamped to the mesh): a glTF primitive.
    size_t first = 0, last = SIZE_MAX;
    /// From the second texture coordinates (MeshData::uv1s, glTF's TEXCOORD_1) rather than the
    /// first: the ones the normal map is sampled with.
    bool secondUvs = false;
    /// If set, only the triangles in the range for which it is true (e.g. those whose material
    /// has a normal map).
    std::function<bool(const MeshData::Triangle&)> select;
};

/// What generateTangents() did.
struct TangentReport {
    size_t triangles = 0;  ///< Triangles given tangents.
    size_t tangents = 0;   ///< Tangents appended to MeshData::tangents.
    size_t fallback = 0;   ///< Of those, ones without a tangent from the uvs (see above).
};

/// Bytes generateTangents() needs while it runs, for `triangles` selected triangles (beyond the
/// tangents it adds): for memory estimates.
size_t tangentGenerationBytes(size_t triangles);

/// Gives the triangles `request` selects tangents at their three corners, appended to
/// `mesh.tangents` (object space, unit length, w = +1 or -1), as MikkTSpace computes them over
/// those triangles together. Triangles without the texture coordinates asked for, or with
/// tangents already, are left as they are. Texture coordinates are Glint's (v up the image):
/// w = +1 where the bitangent N x T points up the image, the glTF and MikkTSpace convention.
TangentReport generateTangents(MeshData& mesh, const TangentRequest& request = {});

}  // namespace glint
