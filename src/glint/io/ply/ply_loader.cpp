// PLY meshes: the header (ply_header.cpp) says which elements follow and how, and
// ply_properties.cpp which of their properties Glint reads; this file checks the file's counts
// against its bytes and the memory available, and reads the elements in order into a MeshData,
// ASCII or binary alike (ply_sources.h).

#include "glint/io/ply/ply_loader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <system_error>
#include <type_traits>

#include "glint/core/mapped_file.h"
#include "glint/io/mesh_memory.h"
#include "glint/io/ply/ply_internal.h"
#include "glint/io/ply/ply_sources.h"

namespace glint {
namespace ply {
namespace {

std::string formatCount(double n) {
    char text[64];
    std::snprintf(text, sizeof text, "%.0f", n);
    return text;
}

[[noreturn]] void failAt(const std::string& file, const Element& e, const std::string& message) {
    throw SceneError({file, e.line, 0}, message);
}

/// Reads a PLY file into a MeshData.
class Reader {
  public:
    Reader(std::string_view bytes, const std::string& file, std::vector<Diagnostic>& warnings,
           const PlyOptions& options)
        : bytes_(bytes), file_(file), warnings_(warnings), options_(options) {
        mesh_.name = file;
    }

    MeshData run();

  private:
    template <class Source>
    void readAll(Source& s);
    template <class Source>
    void readVertices(Source& s, const Element& e);
    template <class Source>
    void readFaces(Source& s, const Element& e, const Layout& l, bool strips);
    template <class Source>
    uint64_t skipElement(Source& s, const Element& e, int countList = -1, bool strips = false);
    void addFace(const uint32_t* v, size_t n, uint32_t uv, uint32_t colour);
    void addTriangle(uint32_t a, uint32_t b, uint32_t c, uint32_t uv, int ka, int kb, int kc,
                     uint32_t colour);

    std::string_view bytes_;
    const std::string& file_;
    std::vector<Diagnostic>& warnings_;
    const PlyOptions& options_;
    Header header_;
    const Element* vertex_ = nullptr;
    Layout vertexLayout_;
    std::vector<Layout> faceLayouts_;  ///< Per element (empty for elements not read as faces).
    MeshData mesh_;
    std::vector<uint32_t> indices_;  ///< Of the face being read.
    std::vector<float> texcoords_;
    size_t smallFaces_ = 0, zeroNormals_ = 0, badUvs_ = 0;
};

template <class Source>
uint64_t Reader::skipElement(Source& s, const Element& e, int countList, bool strips) {
    s.enter(e);
    if (e.properties.empty()) return 0;
    if constexpr (std::is_same_v<Source, BinarySource>) {
        if (!e.hasList()) {  // fixed-size records: one jump
            const size_t size = e.fixedBytes();
            if (e.count > s.remaining() / size) {
                s.at(s.remaining() / size);
                s.truncated();
            }
            s.skipBytes(e.count * size);
            return 0;
        }
    }
    uint64_t triangles = 0;
    for (uint64_t r = 0; r < e.count; ++r) {
        s.at(r);
        for (size_t i = 0; i < e.properties.size(); ++i) {
            const Property& p = e.properties[i];
            if (!p.list) {
                s.skip(p.type);
                continue;
            }
            uint64_t n = s.count(p.countType, p.type);
            s.skipItems(n, p.type);
            if (static_cast<int>(i) == countList) triangles += strips ? n : n >= 3 ? n - 2 : 0;
        }
    }
    return triangles;
}

template <class Source>
void Reader::readVertices(Source& s, const Element& e) {
    s.enter(e);
    const Layout& l = vertexLayout_;
    std::array<double, kRoles> v{};
    std::array<Type, kRoles> types{};
    for (size_t i = 0; i < e.properties.size(); ++i) types[l.roles[i]] = e.properties[i].type;
    // Binary records of fixed size: one bounds check per record, the values Glint uses read
    // at their offsets.
    struct Used {
        Role role;
        Type type;
        size_t offset;
    };
    std::vector<Used> used;
    size_t offset = 0;
    for (size_t i = 0; i < e.properties.size(); ++i) {
        const Property& p = e.properties[i];
        if (l.roles[i] != kSkip) used.push_back({l.roles[i], p.type, offset});
        offset += typeSize(p.list ? p.countType : p.type);
    }
    constexpr bool binary = std::is_same_v<Source, BinarySource>;
    const bool fixed = binary && !e.hasList();
    for (uint64_t r = 0; r < e.count; ++r) {
        s.at(r);
        if constexpr (binary) {
            if (fixed) {
                const unsigned char* record = s.fixedRecord(offset);
                for (const Used& u : used) v[u.role] = s.valueAt(u.type, record + u.offset);
            }
        }
        if (!fixed)
            for (size_t i = 0; i < e.properties.size(); ++i) {
                const Property& p = e.properties[i];
                if (p.list)
                    s.skipItems(s.count(p.countType, p.type), p.type);
                else if (l.roles[i] == kSkip)
                    s.skip(p.type);
                else
                    v[l.roles[i]] = s.real(p.type);
            }
        Vec3f pos(toFloat(v[kX]), toFloat(v[kY]), toFloat(v[kZ]));
        if (!std::isfinite(pos.x) || !std::isfinite(pos.y) || !std::isfinite(pos.z))
            s.fail("vertex coordinates must be finite numbers (at most about 3.4e38)");
        mesh_.positions.push_back(pos);
        if (l.normals) {
            Vec3 n(v[kNx], v[kNy], v[kNz]);
            double len = length(n);
            if (len > 0 && std::isfinite(len)) {
                n = n / len;
            } else {
                n = Vec3(0);
                ++zeroNormals_;
            }
            mesh_.normals.push_back(Vec3f(n));
        }
        if (l.uvs) {
            TexCoord uv{toFloat(v[kU]), toFloat(v[kV])};
            if (!std::isfinite(uv[0]) || !std::isfinite(uv[1])) {
                uv = {0, 0};
                ++badUvs_;
            }
            mesh_.uvs.push_back(uv);
        }
        if (l.colors)
            mesh_.colors.push_back(
                {colourChannel(v[kRed], types[kRed], false),
                 colourChannel(v[kGreen], types[kGreen], false),
                 colourChannel(v[kBlue], types[kBlue], false),
                 l.alpha ? colourChannel(v[kAlpha], types[kAlpha], true) : 1.0f});
    }
}

template <class Source>
void Reader::readFaces(Source& s, const Element& e, const Layout& l, bool strips) {
    s.enter(e);
    const uint64_t vertices = vertex_->count;
    std::array<double, kRoles> v{};
    std::array<Type, kRoles> types{};
    for (size_t i = 0; i < e.properties.size(); ++i) types[l.roles[i]] = e.properties[i].type;
    // Faces bring their own colours and texture coordinates only where vertices have none.
    const bool faceColours = l.colors && !vertexLayout_.colors;
    const bool faceUvs = l.texcoord >= 0 && !vertexLayout_.uvs;
    for (uint64_t r = 0; r < e.count; ++r) {
        s.at(r);
        texcoords_.clear();
        for (size_t i = 0; i < e.properties.size(); ++i) {
            const Property& p = e.properties[i];
            const Role role = l.roles[i];
            if (role == kIndices) {
                uint64_t n = s.count(p.countType, p.type);
                indices_.resize(static_cast<size_t>(n));
                s.indices(p.type, n, indices_.data(), vertices, strips);
            } else if (role == kTexcoord && faceUvs) {
                uint64_t n = s.count(p.countType, p.type);
                for (uint64_t k = 0; k < n; ++k) texcoords_.push_back(toFloat(s.real(p.type)));
            } else if (p.list) {
                s.skipItems(s.count(p.countType, p.type), p.type);
            } else if (role != kSkip && faceColours) {
                v[role] = s.real(p.type);
            } else {
                s.skip(p.type);
            }
        }
        uint32_t colour = MeshData::kNone;
        if (faceColours) {
            colour = static_cast<uint32_t>(mesh_.colors.size());
            mesh_.colors.push_back(
                {colourChannel(v[kRed], types[kRed], false),
                 colourChannel(v[kGreen], types[kGreen], false),
                 colourChannel(v[kBlue], types[kBlue], false),
                 l.alpha ? colourChannel(v[kAlpha], types[kAlpha], true) : 1.0f});
        }
        if (strips) {
            // Runs between -1s; every other triangle turns the other way.
            size_t start = 0;
            for (size_t k = 0; k <= indices_.size(); ++k) {
                if (k < indices_.size() && indices_[k] != kNoIndex) continue;
                for (size_t j = start + 2; j < k; ++j) {
                    bool odd = (j - start) % 2 == 1;
                    addTriangle(indices_[odd ? j - 1 : j - 2], indices_[odd ? j - 2 : j - 1],
                                indices_[j], MeshData::kNone, 0, 0, 0, colour);
                }
                start = k + 1;
            }
            continue;
        }
        uint32_t uv = MeshData::kNone;
        if (faceUvs && texcoords_.size() == 2 * indices_.size() && indices_.size() >= 3) {
            uv = static_cast<uint32_t>(mesh_.uvs.size());
            for (size_t k = 0; k < indices_.size(); ++k) {
                TexCoord t{texcoords_[2 * k], texcoords_[2 * k + 1]};
                if (!std::isfinite(t[0]) || !std::isfinite(t[1])) {
                    t = {0, 0};
                    ++badUvs_;
                }
                mesh_.uvs.push_back(t);
            }
        }
        addFace(indices_.data(), indices_.size(), uv, colour);
    }
}

void Reader::addFace(const uint32_t* v, size_t n, uint32_t uv, uint32_t colour) {
    if (n < 3) {
        ++smallFaces_;
        return;
    }
    for (size_t k = 1; k + 1 < n; ++k)
        addTriangle(v[0], v[k], v[k + 1], uv, 0, static_cast<int>(k), static_cast<int>(k + 1),
                    colour);
}

void Reader::addTriangle(uint32_t a, uint32_t b, uint32_t c, uint32_t uv, int ka, int kb, int kc,
                         uint32_t colour) {
    MeshData::Triangle t;
    const uint32_t ids[3] = {a, b, c};
    const int ks[3] = {ka, kb, kc};
    for (int k = 0; k < 3; ++k) {
        MeshData::Corner& corner = t.corners[static_cast<size_t>(k)];
        corner.position = ids[k];
        if (vertexLayout_.normals) corner.normal = ids[k];
        if (vertexLayout_.uvs)
            corner.uv = ids[k];
        else if (uv != MeshData::kNone)
            corner.uv = uv + static_cast<uint32_t>(ks[k]);
        if (vertexLayout_.colors)
            corner.color = ids[k];
        else if (colour != MeshData::kNone)
            corner.color = colour;
    }
    mesh_.normalTriangles += vertexLayout_.normals;
    mesh_.uvTriangles += t.corners[0].uv != MeshData::kNone;
    mesh_.triangles.push_back(t);
}

template <class Source>
void Reader::readAll(Source& s) {
    for (size_t i = 0; i < header_.elements.size(); ++i) {
        const Element& e = header_.elements[i];
        if (&e == vertex_)
            readVertices(s, e);
        else if (!faceLayouts_[i].roles.empty())
            readFaces(s, e, faceLayouts_[i], e.name == "tristrips");
        else
            skipElement(s, e);
    }
}

MeshData Reader::run() {
    header_ = parseHeader(bytes_, file_);
    faceLayouts_.resize(header_.elements.size());
    double faces = 0;
    for (size_t i = 0; i < header_.elements.size(); ++i) {
        const Element& e = header_.elements[i];
        if (e.name == "vertex") {
            if (vertex_) failAt(file_, e, "a second element 'vertex'");
            vertex_ = &e;
            vertexLayout_ = vertexLayout(e, file_);
            if (e.count >= MeshData::kNone)
                failAt(file_, e,
                       "more vertices than Glint can index (" +
                           std::to_string(MeshData::kNone - 1) + ")");
        } else if ((e.name == "face" || e.name == "tristrips") && e.count > 0) {
            faceLayouts_[i] = faceLayout(e, file_);
            faces += double(e.count);
        }
    }
    if (!vertex_) throw SceneError({file_, 0, 0}, "the file has no element 'vertex'");
    if (faces == 0)
        throw SceneError({file_, 0, 0},
                         "the file has no faces (element 'face'): it is a point cloud, and Glint "
                         "renders surfaces");

    // Every count against the bytes present, before anything is allocated: binary files are
    // walked through once (fixed-size elements in one step), which also counts the triangles;
    // each value of an ASCII file takes at least two bytes.
    const bool binary = header_.format != Format::Ascii;
    double triangles = 0;
    if (binary) {
        BinarySource s(bytes_, header_.dataOffset, header_.format == Format::BinaryBigEndian,
                       file_);
        for (size_t i = 0; i < header_.elements.size(); ++i) {
            const Layout& l = faceLayouts_[i];
            const Element& e = header_.elements[i];
            triangles +=
                double(skipElement(s, e, l.roles.empty() ? -1 : l.indices, e.name == "tristrips"));
        }
    } else {
        double values = 0;
        for (const Element& e : header_.elements)
            values += double(e.count) * double(e.properties.size());
        const size_t data = bytes_.size() - header_.dataOffset;
        if (values * 2 > double(data) + 1)
            throw SceneError({file_, header_.dataLine, 0},
                             "the file is too short for the elements its header announces: " +
                                 std::to_string(data) + " bytes of data for at least " +
                                 formatCount(values) + " values: is it complete?");
        triangles = faces;  // at least one per face (checked again once read)
    }
    const double vertices = double(vertex_->count);
    MeshCounts counts;
    counts.positions = vertices;
    counts.normals = vertexLayout_.normals ? vertices : 0;
    counts.uvs = vertexLayout_.uvs ? vertices : 0;
    counts.colors = vertexLayout_.colors ? vertices : 0;
    counts.triangles = triangles;
    counts.withNormals = vertexLayout_.normals;
    counts.withUvs = vertexLayout_.uvs;
    counts.withColors = vertexLayout_.colors;
    checkMeshMemory(counts, file_, options_.limits);

    // Within the memory checked above: the counts fit a size_t (also a 32-bit one, in WebAssembly).
    const auto vertexCount = static_cast<size_t>(vertex_->count);
    mesh_.positions.reserve(vertexCount);
    if (vertexLayout_.normals) mesh_.normals.reserve(vertexCount);
    if (vertexLayout_.uvs) mesh_.uvs.reserve(vertexCount);
    if (vertexLayout_.colors) mesh_.colors.reserve(vertexCount);
    mesh_.triangles.reserve(static_cast<size_t>(triangles));

    size_t trailing = 0;
    FileLoc trailingAt{file_, 0, 0};
    if (binary) {
        BinarySource s(bytes_, header_.dataOffset, header_.format == Format::BinaryBigEndian,
                       file_);
        readAll(s);
        trailing = s.remaining();
    } else {
        AsciiSource s(bytes_, header_.dataOffset, header_.dataLine, file_);
        readAll(s);
        if (!s.atEnd()) {
            trailing = s.remaining();
            trailingAt = s.here();
        }
    }

    if (mesh_.triangles.empty())
        throw SceneError({file_, 0, 0}, "the file has no faces of 3 or more vertices");
    counts.triangles = double(mesh_.triangles.size());
    counts.uvs = double(mesh_.uvs.size());
    counts.colors = double(mesh_.colors.size());
    counts.withUvs = mesh_.uvTriangles > 0;
    counts.withColors = !mesh_.colors.empty();
    checkMeshMemory(counts, file_, options_.limits);

    auto warn = [&](size_t n, const std::string& what) {
        if (n > 0) warnings_.push_back(warningAt({file_, 0, 0}, std::to_string(n) + " " + what));
    };
    warn(smallFaces_, "faces have fewer than 3 vertices: they are skipped");
    warn(zeroNormals_,
         "vertex normals have zero length or are not finite: they add nothing to interpolated "
         "normals");
    warn(badUvs_, "texture coordinates are not finite numbers: they are taken as 0");
    if (trailing > 0)
        warnings_.push_back(warningAt(trailingAt, std::to_string(trailing) +
                                                      " bytes follow the last element: they are "
                                                      "ignored"));
    return std::move(mesh_);
}

}  // namespace
}  // namespace ply

MeshData parsePly(std::string_view bytes, const std::string& fileName,
                  std::vector<Diagnostic>& warnings, const PlyOptions& options) {
    return ply::Reader(bytes, fileName, warnings, options).run();
}

MeshData loadPly(const std::string& path, std::vector<Diagnostic>& warnings,
                 const PlyOptions& options) {
    if (std::string problem = inputFileProblem(path); !problem.empty())
        throw SceneError({path, 0, 0}, "cannot read PLY: " + problem);
    try {
        MappedFile file(path);
        return parsePly(file.text(), path, warnings, options);
    } catch (const std::system_error& e) {
        throw SceneError({path, 0, 0},
                         std::string("cannot read PLY: ") + std::strerror(e.code().value()));
    }
}

}  // namespace glint
