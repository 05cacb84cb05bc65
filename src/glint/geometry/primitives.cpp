#include "glint/geometry/primitives.h"

#include <ostream>
#include <stdexcept>

namespace glint {

bool Primitives::pushTriangle(const Vec3& a, const Vec3& b, const Vec3& c, uint32_t material) {
    Triangle tri = Triangle::fromVertices(a, b, c);
    if (tri.degenerate()) return false;
    triangles_.push_back(tri);
    triangleMaterial_.push_back(material);
    return true;
}

void Primitives::addAttributes(const Vec3* normals, const TexCoord* uvs) {
    // The per-triangle indices exist only once some triangle has vertex normals or texture
    // coordinates: triangleNormals_ then (kNoNormals for a triangle with coordinates only, so
    // that interaction() tests one index for both), triangleUvs_ once some triangle has
    // coordinates.
    const size_t earlier = triangles_.size() - 1;
    if (triangleNormals_.empty()) triangleNormals_.assign(earlier, kFlat);
    if (normals) {
        triangleNormals_.push_back(static_cast<uint32_t>(vertexNormals_.size()));
        vertexNormals_.push_back({normals[0], normals[1], normals[2]});
    } else {
        triangleNormals_.push_back(uvs ? kNoNormals : kFlat);
    }
    if (uvs || !triangleUvs_.empty()) {
        if (triangleUvs_.empty()) triangleUvs_.assign(earlier, kFlat);
        if (uvs) {
            triangleUvs_.push_back(static_cast<uint32_t>(cornerUvs_.size()));
            cornerUvs_.push_back({uvs[0], uvs[1], uvs[2]});
        } else {
            triangleUvs_.push_back(kFlat);
        }
    }
}

void Primitives::addExtras(const TriangleExtras* extras) {
    const size_t earlier = triangles_.size() - 1;
    if (triangleExtras_.empty()) triangleExtras_.assign(earlier, kFlat);
    if (extras && extras->present) {
        triangleExtras_.push_back(static_cast<uint32_t>(extras_.size()));
        extras_.push_back(*extras);
    } else {
        triangleExtras_.push_back(kFlat);
    }
}

void Primitives::extrasAt(uint32_t id, double b1, double b2, SurfaceInteraction& si) const {
    const uint32_t xi = triangleExtras_[id];
    if (xi == kFlat) return;
    const TriangleExtras& x = extras_[xi];
    const double b0 = 1 - b1 - b2;
    if (x.present & TriangleExtras::kUv1) {
        si.u1 = x.uv1[0][0] * b0 + x.uv1[1][0] * b1 + x.uv1[2][0] * b2;
        si.v1 = x.uv1[0][1] * b0 + x.uv1[1][1] * b1 + x.uv1[2][1] * b2;
        si.hasUv1 = true;
    }
    auto lerp4 = [&](const std::array<std::array<float, 4>, 3>& c, int k) {
        return c[0][k] * b0 + c[1][k] * b1 + c[2][k] * b2;
    };
    if (x.present & TriangleExtras::kColor) {
        si.color = {lerp4(x.color, 0), lerp4(x.color, 1), lerp4(x.color, 2)};
        si.colorAlpha = lerp4(x.color, 3);
        si.hasColor = true;
    }
    if (x.present & TriangleExtras::kTangent) {
        Vec3 t(lerp4(x.tangent, 0), lerp4(x.tangent, 1), lerp4(x.tangent, 2));
        double len = length(t);
        if (len > 0 && std::isfinite(len)) {
            si.tangent = t / len;
            si.tangentSign = x.tangent[0][3] < 0 ? -1 : 1;
            si.hasTangent = true;
        }
    }
}

SurfaceInteraction Primitives::triangleAttributes(uint32_t id, double b1, double b2) const {
    SurfaceInteraction si;
    si.material = triangleMaterial_[id];
    if (uint32_t ti = triangleUvs_.empty() ? kFlat : triangleUvs_[id]; ti != kFlat) {
        const auto& uv = cornerUvs_[ti];
        const double b0 = 1 - b1 - b2;
        si.u = uv[0][0] * b0 + uv[1][0] * b1 + uv[2][0] * b2;
        si.v = uv[0][1] * b0 + uv[1][1] * b1 + uv[2][1] * b2;
        si.hasUv = true;
    }
    if (!triangleExtras_.empty()) extrasAt(id, b1, b2, si);
    return si;
}

void Primitives::addSphere(const Sphere& sphere, uint32_t material) {
    spheres_.push_back(sphere);
    sphereSearch_.push_back(sphereSearch(sphere));
    sphereMaterial_.push_back(material);
}

void Primitives::addShape(const Shape& shape, uint32_t material) {
    shapes_.push_back(shape);
    shapeSearch_.push_back(shape.search());
    shapeMaterial_.push_back(material);
}

void Primitives::addPlane(const Plane& plane, uint32_t material) {
    planes_.push_back(plane);
    planeSearch_.push_back(PlaneSearch::from(plane));
    planeMaterial_.push_back(material);
}

uint32_t Primitives::addSharedMesh(const Primitives& mesh) {
    sharedMeshes_.push_back(&mesh);
    sharedMeshBounds_.push_back(mesh.bounds());
    return static_cast<uint32_t>(sharedMeshes_.size() - 1);
}

const Bounds3f& Primitives::addInstance(uint32_t mesh, const Transform& worldFromObject) {
    const Bounds3f& ob = sharedMeshBounds_[mesh];
    Vec3 lo(kInfinity), hi(-kInfinity);
    if (!ob.empty())
        for (int corner = 0; corner < 8; ++corner) {
            Vec3 p(corner & 1 ? ob.hi.x : ob.lo.x, corner & 2 ? ob.hi.y : ob.lo.y,
                   corner & 4 ? ob.hi.z : ob.lo.z);
            Vec3 w = worldFromObject.point(p);
            lo = min(lo, w);
            hi = max(hi, w);
        }
    Bounds3f bounds = ob.empty() ? Bounds3f() : paddedSearchBounds(lo, hi);
    instances_.push_back(
        {worldFromObject, bounds, ShapeSearch::instance(worldFromObject.inverseMatrix(), mesh)});
    // A deforming mesh is searched beside the tree, with the moving primitives.
    if (sharedMeshes_[mesh]->deformation())
        setMotion(boundedCount() - 1, MotionPath(std::vector{worldFromObject}));
    return instances_.back().bounds;
}

size_t Primitives::instancedTriangleCount() const {
    size_t n = 0;
    for (const Instance& in : instances_) n += sharedMeshes_[in.search.mesh()]->triangleCount();
    return n;
}

bool Primitives::intersectInstance(uint32_t id, const TraversalRay& ray, Hit& hit) const {
    const ShapeSearch& s = shapeSearch(id);
    Vec3f o, d;
    s.map(ray, o, d);
    const TraversalRay local(o, d, ray.tMin, ray.tMax);
    const Primitives& mesh = *sharedMeshes_[s.mesh()];
    Hit sub;
    bool found = false;
    for (uint32_t j = 0; j < mesh.size(); ++j) found |= mesh.intersect(j, local, sub);
    if (!found || !closerHit(sub.t, id, hit)) return false;
    hit = {sub.t, id, sub.primId};
    return true;
}

uint32_t Primitives::shapeCount(ShapeKind kind) const {
    if (kind == ShapeKind::Sphere) return sphereCount();
    if (kind == ShapeKind::Instance) return instanceCount();
    uint32_t n = 0;
    for (const Shape& s : shapes_) n += s.kind == kind;
    return n;
}

void Primitives::reserveAttributes(size_t normals, size_t uvs) {
    if (normals == 0 && uvs == 0) return;
    size_t total = triangles_.capacity();
    triangleNormals_.reserve(total);
    vertexNormals_.reserve(vertexNormals_.size() + normals);
    if (uvs == 0) return;
    triangleUvs_.reserve(total);
    cornerUvs_.reserve(cornerUvs_.size() + uvs);
}

void Primitives::reserve(size_t triangles, size_t spheres, size_t shapes) {
    triangles_.reserve(triangles_.size() + triangles);
    triangleMaterial_.reserve(triangleMaterial_.size() + triangles);
    spheres_.reserve(spheres_.size() + spheres);
    sphereSearch_.reserve(sphereSearch_.size() + spheres);
    sphereMaterial_.reserve(sphereMaterial_.size() + spheres);
    shapes_.reserve(shapes_.size() + shapes);
    shapeSearch_.reserve(shapeSearch_.size() + shapes);
    shapeMaterial_.reserve(shapeMaterial_.size() + shapes);
}

uint32_t Primitives::materialOf(uint32_t id) const {
    if (id < triangleCount()) return triangleMaterial_[id];
    id -= triangleCount();
    if (id < sphereCount()) return sphereMaterial_[id];
    id -= sphereCount();
    if (id < shapeCount()) return shapeMaterial_[id];
    id -= shapeCount();
    if (id < instanceCount()) return kMixedMaterials;
    return planeMaterial_[id - instanceCount()];
}

Bounds3f Primitives::bounds() const {
    Bounds3f b;
    for (uint32_t i = 0; i < boundedCount(); ++i) b.extend(bounds(i));
    if (deformation_) {
        b.extend(deformation_->bounds().lo);
        b.extend(deformation_->bounds().hi);
    }
    return b;
}

void Primitives::setDeformation(std::shared_ptr<const DeformingMesh> d) {
    if (d && d->size() != triangleCount())
        throw std::invalid_argument("a deformation must key every triangle of the mesh");
    deformation_ = std::move(d);
}

void Primitives::setMotion(uint32_t id, MotionPath path) {
    if (id < triangleCount() || id >= boundedCount())
        throw std::invalid_argument("only spheres, shapes and instances move");
    const uint64_t key = motionKey(id);
    auto it = std::lower_bound(motionKeys_.begin(), motionKeys_.end(), key);
    const auto at = it - motionKeys_.begin();
    if (it != motionKeys_.end() && *it == key) {
        motions_[static_cast<size_t>(at)] = std::move(path);
        return;
    }
    motionKeys_.insert(it, key);
    motions_.insert(motions_.begin() + at, std::move(path));
}

namespace {

/// `si`, found in the space `w` maps from, mapped by `w`.
void mapInteraction(SurfaceInteraction& si, const Transform& w) {
    si.p = w.point(si.p);
    si.dpdu = w.vector(si.dpdu);
    if (si.hasTangent) {
        Vec3 t = w.vector(si.tangent);
        double tl = length(t);
        if (tl > 0 && std::isfinite(tl)) si.tangent = t / tl;
        // A mirroring placement turns the frame's handedness.
        if (w.determinant() < 0) si.tangentSign = -si.tangentSign;
    }
    si.ng = normalize(w.normal(si.ng));
    Vec3 n = w.normal(si.n);
    double len = length(n);
    si.n = len > 0 && std::isfinite(len) ? n / len : si.ng;
}

}  // namespace

bool Primitives::intersectMoving(uint32_t id, const MotionPath& m, const TraversalRay& ray,
                                 Hit& hit) const {
    const Transform d = m.delta(shutterTime());
    const Vec3 o = d.inversePoint(Vec3(ray.origin)), dir = d.inverseVector(Vec3(ray.dir));
    const TraversalRay local(Vec3f(o), Vec3f(dir), ray.tMin, ray.tMax);
    if (isInstance(id)) return intersectInstance(id, local, hit);
    float t;
    if (!intersectShape(shapeSearch(id), local, t) || !closerHit(t, id, hit)) return false;
    hit = {t, id};
    return true;
}

SurfaceInteraction Primitives::interaction(const Ray& ray, const Hit& hit) const {
    const MotionPath* m = motion(hit.primId);
    if (!m) [[likely]]
        return stillInteraction(ray, hit);
    // Where the primitive was added, for the ray brought there; then moved back.
    const Transform d = m->delta(shutterTime());
    const Ray local{d.inversePoint(ray.origin), d.inverseVector(ray.dir), ray.tMin, ray.tMax};
    SurfaceInteraction si = stillInteraction(local, hit);
    mapInteraction(si, d);
    return si;
}

SurfaceInteraction Primitives::stillInteraction(const Ray& ray, const Hit& hit) const {
    SurfaceInteraction si;
    if (hit.primId < triangleCount()) {
        const Triangle tri = triangleNow(hit.primId);
        TriangleHit th = refineTriangleHit(tri, ray, hit.t);
        si.p = ray.at(th.t);
        si.ng = normalize(tri.normalDirection());
        si.n = si.ng;
        si.material = triangleMaterial_[hit.primId];
        if (!triangleNormals_.empty()) {  // some triangle has vertex normals or coordinates
            const double b0 = 1 - th.b1 - th.b2;
            if (uint32_t ni = triangleNormals_[hit.primId]; ni != kFlat && ni != kNoNormals) {
                const std::array<Vec3, 3>* corners = &vertexNormals_[ni];
                std::array<Vec3, 3> keyed;
                if (deformation_ && deformation_->hasNormals()) [[unlikely]] {
                    const auto now = deformation_->normalsAt(hit.primId, shutterTime());
                    keyed = {Vec3(now[0]), Vec3(now[1]), Vec3(now[2])};
                    corners = &keyed;
                }
                const auto& vn = *corners;
                Vec3 n = vn[0] * b0 + vn[1] * th.b1 + vn[2] * th.b2;
                double len = length(n);
                // Opposed or zero vertex normals can cancel: keep the geometric normal then.
                if (len > 0 && std::isfinite(len)) si.n = n / len;
            }
            if (uint32_t ti = triangleUvs_.empty() ? kFlat : triangleUvs_[hit.primId];
                ti != kFlat) {
                const auto& uv = cornerUvs_[ti];
                si.u = uv[0][0] * b0 + uv[1][0] * th.b1 + uv[2][0] * th.b2;
                si.v = uv[0][1] * b0 + uv[1][1] * th.b1 + uv[2][1] * th.b2;
                si.hasUv = true;
                // dp/du from the edges and their coordinate differences.
                const Vec3 e1 = Vec3(tri.v1) - Vec3(tri.v0), e2 = Vec3(tri.v2) - Vec3(tri.v0);
                const double du1 = uv[1][0] - uv[0][0], dv1 = uv[1][1] - uv[0][1];
                const double du2 = uv[2][0] - uv[0][0], dv2 = uv[2][1] - uv[0][1];
                const double det = du1 * dv2 - du2 * dv1;
                if (det != 0) si.dpdu = (e1 * dv2 - e2 * dv1) / det;
            }
        }
        // Not under the test above: a triangle may have colours without normals (a PLY scan).
        if (!triangleExtras_.empty()) extrasAt(hit.primId, th.b1, th.b2, si);
    } else if (uint32_t i = hit.primId - triangleCount(); i < sphereCount()) {
        const Sphere& s = spheres_[i];
        Vec3 local;
        double t = refineSphereHit(s, ray, hit.t, local);
        si.p = ray.at(t);
        si.ng = normalize(s.worldFromObject.normal(local));
        si.n = si.ng;
        si.material = sphereMaterial_[i];
    } else {
        // Shapes and planes out of line: the triangle and sphere paths stay lean.
        return shapeInteraction(ray, hit);
    }
    return si;
}

SurfaceInteraction Primitives::shapeInteraction(const Ray& ray, const Hit& hit) const {
    SurfaceInteraction si;
    if (isInstance(hit.primId)) {
        // The mesh's own interaction for the ray in its space (the direction is not
        // renormalised, so t is the same), mapped back to world space.
        const Instance& in =
            instances_[hit.primId - triangleCount() - sphereCount() - shapeCount()];
        const Transform& w = in.worldFromObject;
        Ray local{w.inversePoint(ray.origin), w.inverseVector(ray.dir), ray.tMin, ray.tMax};
        si = sharedMeshes_[in.search.mesh()]->interaction(local, Hit{hit.t, hit.subId});
        mapInteraction(si, w);
    } else if (hit.primId < boundedCount()) {
        uint32_t i = hit.primId - triangleCount() - sphereCount();
        const Shape& s = shapes_[i];
        Vec3 local;
        double t = refineShapeHit(s, ray, hit.t, local);
        si.p = ray.at(t);
        si.ng = normalize(s.worldFromCanonical.normal(canonicalNormal(s.kind, s.k, local)));
        si.n = si.ng;
        si.material = shapeMaterial_[i];
    } else {
        uint32_t i = hit.primId - boundedCount();
        si.p = ray.at(refinePlaneHit(planes_[i], ray, hit.t));
        si.ng = planes_[i].normal;
        si.n = si.ng;
        si.material = planeMaterial_[i];
    }
    return si;
}

std::ostream& operator<<(std::ostream& out, const SurfaceInteraction& si) {
    out << "SurfaceInteraction{p " << si.p << ", n " << si.n << ", ng " << si.ng << ", material "
        << si.material;
    if (si.hasUv) out << ", uv (" << si.u << ", " << si.v << ')';
    return out << '}';
}

}  // namespace glint
