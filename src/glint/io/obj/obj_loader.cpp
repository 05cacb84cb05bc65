// Wavefront OBJ through tinyobjloader's callback interface: the library reads each statement
// and hands over numbers and raw indices; this file checks them (with the statement's line and
// column), resolves relative indices, triangulates polygons and builds the MeshData directly,
// without the library's own copy of the whole mesh.

#include "glint/io/obj/obj_loader.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <istream>
#include <set>
#include <system_error>

#include "glint/core/mapped_file.h"
#include "glint/core/system.h"
#include "glint/geometry/polygon.h"
#include "glint/io/obj/obj_internal.h"
#include "glint/scene/tangents.h"

namespace glint {
namespace obj {
namespace {

/// Polygons up to this many vertices are triangulated by ear clipping (quadratic time); larger
/// ones, and polygons ear clipping rejects (not planar, self-intersecting), as a fan.
constexpr int kMaxEarClippedVertices = 1024;

/// Upper bounds of what an OBJ text holds, from its lines' first words, so that storage is
/// reserved once and the memory it needs is known before anything is allocated.
struct Counts {
    size_t positions = 0, normals = 0, uvs = 0, triangles = 0;
};

Counts countStatements(std::string_view text) {
    Counts c;
    const char* p = text.data();
    const char* end = p + text.size();
    while (p < end) {
        while (p < end && (*p == ' ' || *p == '\t')) ++p;
        const char* eol = static_cast<const char*>(std::memchr(p, '\n', size_t(end - p)));
        if (!eol) eol = end;
        if (end - p >= 2 && p[0] == 'v' && (p[1] == ' ' || p[1] == '\t')) {
            ++c.positions;
        } else if (end - p >= 3 && p[0] == 'v' && (p[2] == ' ' || p[2] == '\t')) {
            c.normals += p[1] == 'n';
            c.uvs += p[1] == 't';
        } else if (end - p >= 2 && p[0] == 'f' && (p[1] == ' ' || p[1] == '\t')) {
            size_t words = 0;
            bool inWord = false;
            for (const char* q = p + 1; q < eol && *q != '#'; ++q) {
                bool blank = *q == ' ' || *q == '\t' || *q == '\r';
                words += !blank && !inWord;
                inWord = !blank;
            }
            c.triangles += words >= 3 ? words - 2 : 0;
        }
        p = eol + (eol < end);
    }
    return c;
}

/// Reads one OBJ text into a MeshData. Callbacks throw SceneError, which passes through the
/// library (it holds nothing but standard containers).
class Reader : public tinyobj::MaterialReader {
  public:
    Reader(std::string_view text, const std::string& file, std::vector<Diagnostic>& warnings,
           const ObjOptions& options)
        : text_(text), file_(file), warnings_(warnings), options_(options) {
        mesh_.name = file;
        std::filesystem::path dir = std::filesystem::path(file).parent_path();
        dir_ = dir.string();
    }

    MeshData run();

    // tinyobj::MaterialReader: reads the library `name` of an `mtllib` statement.
    bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* map, std::string* warn, std::string* err) override;

  private:
    FileLoc here(int token = 0) const {
        return statementAt(text_, base_ + buf_->offset(), file_, token);
    }
    [[noreturn]] void fail(const std::string& message, int token = 0) const {
        throw SceneError(here(token), message);
    }
    void warnOnce(bool& done, const std::string& message) {
        if (done) return;
        warnings_.push_back({here(), message + " (reported once)"});
        done = true;
    }

    static Reader& self(void* p) { return *static_cast<Reader*>(p); }
    static void onVertex(void* p, float x, float y, float z, float w);
    static void onNormal(void* p, float x, float y, float z);
    static void onTexCoord(void* p, float u, float v, float w);
    static void onFace(void* p, tinyobj::index_t* indices, int count);
    static void onUseMaterial(void* p, const char* name, int id);
    static void onMaterials(void* p, const tinyobj::material_t* materials, int count);

    /// Index `raw` of corner `k` into a list of `count` entries named `what`: 1-based, or
    /// negative to count back from the end. 0 means absent except for positions.
    uint32_t resolve(int raw, size_t count, const char* what, int k) const;
    [[noreturn, gnu::cold]] void badIndex(int raw, size_t count, const char* what, int k) const;
    void addFace(const tinyobj::index_t* indices, int count);
    void addTriangle(const MeshData::Corner& a, const MeshData::Corner& b,
                     const MeshData::Corner& c);

    std::string_view text_;
    const std::string& file_;
    std::vector<Diagnostic>& warnings_;
    const ObjOptions& options_;
    std::string dir_;
    size_t base_ = 0;  ///< Bytes skipped before the stream (a byte-order mark).
    TextBuf* buf_ = nullptr;
    MeshData mesh_;

    std::vector<std::string> mtlFiles_;  ///< The library each material came from...
    std::vector<MtlEntry> mtlEntries_;   ///< ...and what it has.
    size_t mapped_ = 0;                  ///< Materials already in mesh_.materials.
    std::map<std::string, uint32_t> materialIds_;
    uint32_t material_ = MeshData::kNone;
    TextureCache textures_;
    std::vector<MeshData::Corner> corners_;   ///< Of the face being read.
    std::vector<Vec3> polygon_;               ///< Positions of the face being triangulated.
    std::set<std::string> unknownMaterials_;  ///< Named by usemtl and warned about.
    int unreadLibraries_ =
        0;  ///< mtllib files not read (warned about): their materials are unknown.
    bool warnedNormal_ = false, warnedMixed_ = false, warnedFan_ = false;
};

std::string trimmed(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
        s.remove_suffix(1);
    return std::string(s);
}

void Reader::onVertex(void* p, float x, float y, float z, float) {
    Reader& r = self(p);
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
        r.fail("vertex coordinates must be finite numbers (at most about 3.4e38)");
    r.mesh_.positions.push_back({x, y, z});
}

void Reader::onNormal(void* p, float x, float y, float z) {
    Reader& r = self(p);
    Vec3 n(x, y, z);
    if (!isFinite(n)) r.fail("normal components must be finite numbers");
    double len = length(n);
    if (!(len > 0) || !std::isfinite(len)) {
        r.warnOnce(r.warnedNormal_,
                   "normal has zero length: it adds nothing to interpolated normals");
        n = Vec3(0);
    } else {
        n = n / len;
    }
    r.mesh_.normals.push_back(Vec3f(n));
}

void Reader::onTexCoord(void* p, float u, float v, float) {
    Reader& r = self(p);
    if (!std::isfinite(u) || !std::isfinite(v))
        r.fail("texture coordinates must be finite numbers");
    r.mesh_.uvs.push_back({u, v});
}

uint32_t Reader::resolve(int raw, size_t count, const char* what, int k) const {
    long long i = raw > 0 ? raw - 1LL : static_cast<long long>(count) + raw;
    if (i < 0 || static_cast<size_t>(i) >= count) badIndex(raw, count, what, k);
    return static_cast<uint32_t>(i);
}

void Reader::badIndex(int raw, size_t count, const char* what, int k) const {
    // Built by appending: GCC 12 warns falsely on "'" + string.
    std::string msg(what);
    msg.append(" index '").append(std::to_string(raw)).append("' ");
    msg.append(raw < 0 ? "counts back past the first " : "is out of range");
    if (raw < 0) msg.append(what);
    msg.append(": ");
    if (count == 0) {
        msg.append("none is defined before it");
    } else {
        msg.append(std::to_string(count)).append(" ");
        if (count == 1)
            msg.append(what).append(" is");
        else if (std::string_view(what) == "vertex")
            msg.append("vertices are");
        else
            msg.append(what).append("s are");
        msg.append(" defined before it");
    }
    fail(msg, k + 1);
}

void Reader::onFace(void* p, tinyobj::index_t* indices, int count) {
    self(p).addFace(indices, count);
}

void Reader::addFace(const tinyobj::index_t* indices, int count) {
    if (count < 3)
        fail("a face needs at least 3 vertices, got " + std::to_string(count), count > 0 ? 1 : 0);
    std::vector<MeshData::Corner>& corners = corners_;  // reused: no allocation per face
    corners.assign(static_cast<size_t>(count), MeshData::Corner{});
    int withNormal = 0, withUv = 0;
    for (int k = 0; k < count; ++k) {
        const tinyobj::index_t& ix = indices[k];
        if (ix.vertex_index == 0)
            fail("vertex index '0' is not valid: OBJ indices start at 1 (or count back from -1)",
                 k + 1);
        MeshData::Corner& c = corners[static_cast<size_t>(k)];
        c.position = resolve(ix.vertex_index, mesh_.positions.size(), "vertex", k);
        if (ix.normal_index != 0) {
            c.normal = resolve(ix.normal_index, mesh_.normals.size(), "normal", k);
            ++withNormal;
        }
        if (ix.texcoord_index != 0) {
            c.uv = resolve(ix.texcoord_index, mesh_.uvs.size(), "texture coordinate", k);
            ++withUv;
        }
    }
    // A triangle has normals (and coordinates) at all its corners or at none.
    if ((withNormal > 0 && withNormal < count) || (withUv > 0 && withUv < count)) {
        warnOnce(warnedMixed_,
                 "face has normals or texture coordinates at some corners only: it goes without "
                 "them");
        for (MeshData::Corner& c : corners) {
            if (withNormal < count) c.normal = MeshData::kNone;
            if (withUv < count) c.uv = MeshData::kNone;
        }
    }
    if (count == 3) return addTriangle(corners[0], corners[1], corners[2]);
    polygon_.clear();
    for (const MeshData::Corner& c : corners) polygon_.push_back(Vec3(mesh_.positions[c.position]));
    const std::vector<Vec3>& q = polygon_;
    if (count == 4) {
        // Split along the diagonal whose two triangles face the same way (a concave quad has
        // one), the shorter one when both do (the better fit for a quad that is not planar).
        Vec3 n0 = cross(q[1] - q[0], q[2] - q[0]), n1 = cross(q[2] - q[0], q[3] - q[0]);
        Vec3 m0 = cross(q[1] - q[0], q[3] - q[0]), m1 = cross(q[2] - q[1], q[3] - q[1]);
        bool along02 = dot(n0, n1) > 0, along13 = dot(m0, m1) > 0;
        if (along02 && along13) {
            Vec3 d02 = q[2] - q[0], d13 = q[3] - q[1];
            along02 = dot(d02, d02) <= dot(d13, d13);
        }
        if (along02 || !along13) {
            addTriangle(corners[0], corners[1], corners[2]);
            addTriangle(corners[0], corners[2], corners[3]);
        } else {
            addTriangle(corners[0], corners[1], corners[3]);
            addTriangle(corners[1], corners[2], corners[3]);
        }
        return;
    }
    if (count <= kMaxEarClippedVertices) {
        PolygonTriangulation poly = triangulatePolygon(q);
        if (poly.problem == PolygonTriangulation::Problem::None) {
            for (const auto& t : poly.triangles)
                addTriangle(corners[t[0]], corners[t[1]], corners[t[2]]);
            return;
        }
    }
    warnOnce(warnedFan_,
             "polygon of " + std::to_string(count) +
                 " vertices is not planar, not simple or too large to split by ear clipping: it "
                 "is split as a fan from its first vertex");
    for (int k = 1; k + 1 < count; ++k)
        addTriangle(corners[0], corners[static_cast<size_t>(k)],
                    corners[static_cast<size_t>(k + 1)]);
}

void Reader::addTriangle(const MeshData::Corner& a, const MeshData::Corner& b,
                         const MeshData::Corner& c) {
    mesh_.triangles.push_back({{a, b, c}, material_});
    mesh_.normalTriangles += a.normal != MeshData::kNone;
    mesh_.uvTriangles += a.uv != MeshData::kNone;
}

void Reader::onUseMaterial(void* p, const char* name, int) {
    Reader& r = self(p);
    std::string key = trimmed(name);
    auto it = r.materialIds_.find(key);
    if (it != r.materialIds_.end()) {
        r.material_ = it->second;
        return;
    }
    r.material_ = MeshData::kNone;
    // A library that could not be read was warned about: its materials are not named again.
    if (r.unreadLibraries_ > 0 || !r.unknownMaterials_.insert(key).second) return;
    r.warnings_.push_back({r.here(1), "material '" + key +
                                          "' is not defined in any material library (mtllib): "
                                          "its faces take the default material"});
}

void Reader::onMaterials(void* p, const tinyobj::material_t* materials, int count) {
    // Called after each library with all materials so far: map the new ones.
    Reader& r = self(p);
    for (size_t i = r.mapped_; i < static_cast<size_t>(count); ++i) {
        MtlSource source;
        source.file = i < r.mtlFiles_.size() ? r.mtlFiles_[i] : r.file_;
        source.readTextures = r.options_.limits.readFiles && !r.options_.mtlText;
        if (source.readTextures)
            source.textureDir = std::filesystem::path(source.file).parent_path().string();
        MtlEntry entry = i < r.mtlEntries_.size() ? r.mtlEntries_[i] : MtlEntry{};
        MeshMaterial m = mapMtlMaterial(materials[i], entry, source, r.textures_, r.warnings_,
                                        r.options_.limits);
        r.materialIds_.emplace(trimmed(m.name), static_cast<uint32_t>(r.mesh_.materials.size()));
        r.mesh_.materials.push_back(std::move(m));
    }
    r.mapped_ = std::max(r.mapped_, static_cast<size_t>(count));
}

bool Reader::operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                        std::map<std::string, int>* map, std::string* warn, std::string* err) {
    std::string label = name;
    std::string text;
    std::unique_ptr<MappedFile> file;
    std::string_view mtl;
    if (options_.mtlText) {
        mtl = *options_.mtlText;
    } else if (!options_.limits.readFiles) {
        warnings_.push_back({here(1), "material library '" + name +
                                          "' is not read (reading "
                                          "files is turned off)"});
        ++unreadLibraries_;
        return false;
    } else {
        std::string path = name;
        std::replace(path.begin(), path.end(), '\\', '/');
        if (!path.empty() && path.front() != '/' && !dir_.empty()) path = dir_ + "/" + path;
        label = path;
        std::string problem = inputFileProblem(path);
        if (problem.empty()) {
            try {
                file = std::make_unique<MappedFile>(path);
            } catch (const std::system_error& e) {
                problem = std::strerror(e.code().value());
            }
        }
        if (!problem.empty()) {
            // As other viewers do: the model without the library's materials.
            warnings_.push_back({here(1), "cannot read material library '" + name + "' (" + path +
                                              "): " + problem +
                                              "; faces that use its materials take the default "
                                              "material"});
            ++unreadLibraries_;
            return false;
        }
        mtl = file->text();
    }
    if (mtl.starts_with("\xEF\xBB\xBF")) mtl.remove_prefix(3);
    std::vector<MtlEntry> entries = scanMtl(mtl);
    size_t before = materials->size();
    TextBuf buf(mtl);
    std::istream in(&buf);
    std::string mtlWarnings;
    tinyobj::LoadMtl(map, materials, &in, &mtlWarnings, err);
    for (size_t i = before; i < materials->size(); ++i) {
        mtlFiles_.push_back(label);
        mtlEntries_.push_back(i - before < entries.size() ? entries[i - before] : MtlEntry{});
    }
    // The library's own remarks (e.g. both d and Tr given), at their line of the library.
    for (Diagnostic& d : libraryWarnings(mtlWarnings, label)) warnings_.push_back(std::move(d));
    (void)warn;
    return true;
}

MeshData Reader::run() {
    if (text_.starts_with("\xEF\xBB\xBF")) base_ = 3;  // a UTF-8 byte-order mark
    Counts counts = countStatements(text_);
    size_t needed = objBytes(counts.positions, counts.normals, counts.uvs, counts.triangles);
    size_t available = memoryAvailable(options_.limits);
    if (available > 0 && needed > available)
        throw SceneError({file_, 0, 0},
                         "the mesh needs about " + formatBytes(static_cast<double>(needed)) +
                             " of memory (" + std::to_string(counts.triangles) +
                             " triangles), more than the " +
                             formatBytes(static_cast<double>(available)) + " available");
    mesh_.positions.reserve(counts.positions);
    mesh_.normals.reserve(counts.normals);
    mesh_.uvs.reserve(counts.uvs);
    mesh_.triangles.reserve(counts.triangles);

    TextBuf buf(text_.substr(base_));
    buf_ = &buf;
    std::istream in(&buf);
    tinyobj::callback_t cb;
    cb.vertex_cb = onVertex;
    cb.normal_cb = onNormal;
    cb.texcoord_cb = onTexCoord;
    cb.index_cb = onFace;
    cb.usemtl_cb = onUseMaterial;
    cb.mtllib_cb = onMaterials;
    std::string warn, err;
    try {
        tinyobj::LoadObjWithCallback(in, cb, this, this, &warn, &err);
    } catch (const SceneError&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw;
    } catch (const std::exception& e) {
        // The library's own failures (it reports few), at the statement it was reading.
        fail(std::string("cannot read the mesh: ") + e.what());
    }
    // The library's own remarks. Its note that a library failed repeats Glint's warning.
    for (Diagnostic& d : libraryWarnings(warn, file_))
        if (!(unreadLibraries_ > 0 &&
              d.message.find("Failed to load material file") != std::string::npos))
            warnings_.push_back(std::move(d));
    if (mesh_.triangles.empty())
        throw SceneError({file_, 0, 0},
                         "the mesh has no faces ('f' statements): is the file complete?");
    if (!text_.empty() && text_.back() != '\n' && text_.back() != '\r')
        warnings_.push_back({here(), "the last line has no line break: the file may be truncated"});
    // Faces whose material has a normal map get MikkTSpace's tangents, as glTF's would.
    std::vector<bool> normalMapped(mesh_.materials.size());
    bool any = false;
    for (size_t i = 0; i < mesh_.materials.size(); ++i) {
        const auto& pbr = mesh_.materials[i].pbr;
        normalMapped[i] = pbr && pbr->normalTexture;
        any = any || normalMapped[i];
    }
    if (any && mesh_.uvTriangles > 0) {
        TangentRequest request;
        request.select = [&](const MeshData::Triangle& t) {
            return t.material != MeshData::kNone && normalMapped[t.material];
        };
        generateTangents(mesh_, request);
    }
    return std::move(mesh_);
}

}  // namespace
}  // namespace obj

size_t objBytes(size_t positions, size_t normals, size_t uvs, size_t triangles) {
    size_t mesh = positions * sizeof(Vec3f) + normals * sizeof(Vec3f) + uvs * sizeof(TexCoord) +
                  triangles * sizeof(MeshData::Triangle);
    return mesh +
           Scene::estimateBytes(triangles, 0, 0, normals ? triangles : 0, uvs ? triangles : 0) +
           meshPlacementBytes(positions, normals);
}

MeshData parseObj(std::string_view text, const std::string& fileName,
                  std::vector<Diagnostic>& warnings, const ObjOptions& options) {
    return obj::Reader(text, fileName, warnings, options).run();
}

MeshData loadObj(const std::string& path, std::vector<Diagnostic>& warnings,
                 const ObjOptions& options) {
    if (std::string problem = inputFileProblem(path); !problem.empty())
        throw SceneError({path, 0, 0}, "cannot read mesh: " + problem);
    try {
        MappedFile file(path);
        return parseObj(file.text(), path, warnings, options);
    } catch (const std::system_error& e) {
        throw SceneError({path, 0, 0},
                         std::string("cannot read mesh: ") + std::strerror(e.code().value()));
    }
}

}  // namespace glint
