// The table of file formats and the choice of one for a file (registry.h).

#include "glint/io/registry.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "glint/io/course/course_loader.h"
#include "glint/io/gltf/gltf_loader.h"
#include "glint/io/obj/obj_loader.h"
#include "glint/io/ply/ply_loader.h"
#include "glint/io/stl/stl_loader.h"
#include "glint/math/motion.h"

namespace glint {
namespace {

/// `text` without a UTF-8 byte-order mark and blanks at its start.
std::string_view trimmedStart(std::string_view text) {
    if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);
    size_t i = text.find_first_not_of(" \t\r\n");
    return i == std::string_view::npos ? std::string_view() : text.substr(i);
}

/// Whether `text` starts with `word` followed by a blank or its end.
bool startsWithWord(std::string_view text, std::string_view word) {
    if (!text.starts_with(word)) return false;
    if (text.size() == word.size()) return true;
    char c = text[word.size()];
    return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

bool gltfMagic(std::string_view head, uint64_t) {
    if (head.starts_with("glTF")) return true;  // a .glb
    std::string_view text = trimmedStart(head);
    return text.starts_with("{") && text.find("\"asset\"") != std::string_view::npos;
}

bool plyMagic(std::string_view head, uint64_t) { return startsWithWord(head, "ply"); }

bool stlMagic(std::string_view head, uint64_t size) {
    // Binary: an 80-byte header, a little-endian triangle count, 50 bytes per triangle.
    if (head.size() >= 84) {
        uint64_t count = 0;
        for (int i = 3; i >= 0; --i) count = count << 8 | static_cast<unsigned char>(head[80 + i]);
        if (size == binaryStlBytes(count)) return true;
    }
    return startsWithWord(trimmedStart(head), "solid");
}

bool fbxMagic(std::string_view head, uint64_t) {
    return head.starts_with("Kaydara FBX Binary") || trimmedStart(head).starts_with("; FBX");
}

bool blenderMagic(std::string_view head, uint64_t) { return head.starts_with("BLENDER"); }

std::unique_ptr<Scene> loadCourse(const std::string& path, std::vector<Diagnostic>& warnings,
                                  const LoadOptions& options) {
    CourseOptions course;
    course.limits = options.limits;
    course.lenient = options.lenient;
    course.time = options.time;
    course.assets = options.assets;
    return loadCourseScene(path, warnings, course);
}

Model loadObjModel(const std::string& path, std::vector<Diagnostic>& warnings,
                   const LoadOptions& options) {
    ObjOptions obj;
    obj.limits = options.limits;
    return singleMeshModel(loadObj(path, warnings, obj));
}

/// Moves the placements, meshes and camera of `model` (posed at the shutter's middle) as the
/// animation moves them over the shutter of `time`: each placement whose transform changes
/// gets its transforms at the shutter's keys (ModelPlacement::motion); each mesh whose vertices
/// change (skins, morph targets) its vertices at the keys (MeshData::positionKeys); the camera
/// its specs.
void addMotion(GltfDocument& asset, const ModelTime& time, Model& model,
               std::vector<Diagnostic>& warnings) {
    std::vector<Model> keys;
    for (int k = 0; k < time.shutterKeys; ++k) {
        ModelTime at = time;
        at.seconds = time.keyTime(k);
        at.shutterOpen = at.shutterClose = 0;
        keys.push_back(asset.pose(at, warnings));
    }
    for (size_t i = 0; i < model.placements.size(); ++i) {
        std::vector<Transform> path;
        for (const Model& m : keys) {
            if (m.placements.size() != model.placements.size()) return;  // cannot happen
            path.push_back(m.placements[i].worldFromObject);
        }
        if (MotionPath(path).moves()) model.placements[i].motion = std::move(path);
    }
    for (size_t i = 0; i < model.meshes.size(); ++i) {
        MeshData& mesh = model.meshes[i];
        bool alike = true, deforms = false;
        for (const Model& m : keys) {
            if (m.meshes.size() != model.meshes.size()) return;  // cannot happen
            const MeshData& at = m.meshes[i];
            const MeshData& first = keys.front().meshes[i];
            alike = alike && at.positions.size() == mesh.positions.size() &&
                    at.normals.size() == mesh.normals.size();
            deforms = deforms || (alike && !std::equal(at.positions.begin(), at.positions.end(),
                                                       first.positions.begin()));
        }
        if (!alike || !deforms) continue;
        for (Model& m : keys) {
            mesh.positionKeys.push_back(std::move(m.meshes[i].positions));
            mesh.normalKeys.push_back(std::move(m.meshes[i].normals));
        }
    }
    if (model.camera) {
        bool moves = false;
        for (const Model& m : keys) {
            if (!m.camera) return;
            model.cameraMotion.push_back(m.camera->spec);
            const CameraSpec &a = m.camera->spec, &b = keys.front().camera->spec;
            moves = moves || !(a.eye == b.eye && a.center == b.center && a.up == b.up &&
                               a.fovyDegrees == b.fovyDegrees);
        }
        if (!moves) model.cameraMotion.clear();
    }
}

/// Poses at which an animated model's bounds are taken for framing: evenly spaced over its
/// animation, both ends included.
constexpr int kFramingPoses = 9;

Model loadGltfModel(const std::string& path, std::vector<Diagnostic>& warnings,
                    const LoadOptions& options) {
    GltfOptions gltf;
    gltf.limits = options.limits;
    gltf.camera = options.camera;
    gltf.variant = options.variant;
    // The camera choice is applied while posing, the variant while parsing: both are part of
    // what is cached.
    const std::string key = path + '\n' + options.camera.describe() + '\n' + options.variant;
    std::shared_ptr<GltfDocument> asset = options.assets ? options.assets->find(key) : nullptr;
    if (!asset) {
        asset = openGltf(path, warnings, gltf);
        if (options.assets) options.assets->add(key, asset);
    }
    ModelTime middle = options.time;
    if (middle.blurs()) {  // the still parts, and deforming meshes, at the shutter's middle
        middle.seconds =
            middle.seconds.value_or(0) + (middle.shutterOpen + middle.shutterClose) / 2;
        middle.shutterOpen = middle.shutterClose = 0;
    }
    Model model = asset->pose(middle, warnings);
    if (options.time.blurs() && model.animation) addMotion(*asset, options.time, model, warnings);
    if (model.animation) {
        // Framed by the whole animation, whichever frame this is: each frame of a sequence, in
        // one process or many, gets the same camera and ground.
        const ModelAnimation& a = asset->animations()[*model.animation];
        Bounds3f b;
        for (int i = 0; i < kFramingPoses; ++i) {
            ModelTime t = options.time;
            t.seconds = a.start + (a.end - a.start) * i / (kFramingPoses - 1);
            b.extend(asset->pose(t, warnings).bounds());
        }
        model.frameBounds = b;
    }
    return model;
}

/// Loads a model with `format`, and applies the camera choice where its loader has not (a
/// format without cameras).
Model loadModelAs(const FileFormat& format, const std::string& path,
                  std::vector<Diagnostic>& warnings, const LoadOptions& options) {
    Model model = format.loadModel(path, warnings, options);
    switch (options.camera.kind) {
        case CameraChoice::Kind::None:
            model.camera.reset();
            model.cameraMotion.clear();
            break;
        case CameraChoice::Kind::Orbit:
            model.camera =
                ModelCamera{options.camera.orbit.spec(), 0, options.camera.orbit.describe(), false};
            model.cameraMotion.clear();
            break;
        case CameraChoice::Kind::Index:
        case CameraChoice::Kind::Name:
            if (!model.camera)
                throw SceneError({path, 0, 0}, "there is no " + options.camera.describe() + ": " +
                                                   format.name + " files have no cameras");
            break;
        default:
            break;
    }
    return model;
}

Model loadPlyModel(const std::string& path, std::vector<Diagnostic>& warnings,
                   const LoadOptions& options) {
    PlyOptions ply;
    ply.limits = options.limits;
    return singleMeshModel(loadPly(path, warnings, ply));
}

Model loadStlModel(const std::string& path, std::vector<Diagnostic>& warnings,
                   const LoadOptions& options) {
    StlOptions stl;
    stl.limits = options.limits;
    return singleMeshModel(loadStl(path, warnings, stl));
}

/// Whether `head` is not text: it has a NUL byte, or control characters other than blanks in
/// more than 1 byte of 32 (text in any 8-bit encoding or UTF-8 has none).
bool looksBinary(std::string_view head) {
    size_t controls = 0;
    for (char ch : head) {
        unsigned char c = static_cast<unsigned char>(ch);
        if (c == 0) return true;
        controls += (c < 0x20 && !(c >= '\t' && c <= '\r')) || c == 0x7F;
    }
    return controls * 32 > head.size();
}

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

bool readsFor(const FileFormat& f, FileUse use) {
    return f.loadModel || (use == FileUse::Scene && f.loadScene);
}

/// "it reads CSE167x scenes (.test), OBJ (.obj) and glTF (.gltf, .glb)", or for meshes "it
/// reads meshes from OBJ (.obj) and glTF (.gltf, .glb)".
std::string whatGlintReads(FileUse use) {
    std::vector<std::string> items;
    for (const FileFormat& f : fileFormats()) {
        if (!readsFor(f, use)) continue;
        std::string item = std::string(f.listed) + " (";
        for (size_t i = 0; i < f.extensions.size(); ++i)
            item.append(i ? ", " : "").append(f.extensions[i]);
        items.push_back(item + ")");
    }
    std::string list;
    for (size_t i = 0; i < items.size(); ++i)
        list += (i == 0 ? "" : i + 1 == items.size() ? " and " : ", ") + items[i];
    return (use == FileUse::Scene ? "it reads " : "it reads meshes from ") + list;
}

FormatChoice cannotRead(const std::string& what, FileUse use) {
    return {nullptr, what + "; " + whatGlintReads(use)};
}

}  // namespace

std::shared_ptr<GltfDocument> AssetCache::find(const std::string& key) const {
    for (const auto& [k, asset] : assets_)
        if (k == key) return asset;
    return nullptr;
}

void AssetCache::add(const std::string& key, std::shared_ptr<GltfDocument> asset) {
    assets_.emplace_back(key, std::move(asset));
}

std::shared_ptr<const Model> AssetCache::findModel(const std::string& key) const {
    for (const auto& [k, model] : models_)
        if (k == key) return model;
    return nullptr;
}

void AssetCache::addModel(const std::string& key, std::shared_ptr<const Model> model) {
    models_.emplace_back(key, std::move(model));
}

std::shared_ptr<const Model> loadModelFile(const FileFormat& format, const std::string& path,
                                           std::vector<Diagnostic>& warnings,
                                           const LoadOptions& options) {
    // glTF files have time: their parsed documents are cached, and posed for each frame.
    const bool still = format.loadModel != loadGltfModel;
    const std::string key = path + '\n' + options.camera.describe();
    if (still && options.assets)
        if (std::shared_ptr<const Model> kept = options.assets->findModel(key)) return kept;
    auto model = std::make_shared<const Model>(loadModelAs(format, path, warnings, options));
    if (still && options.assets) options.assets->addModel(key, model);
    return model;
}

const std::vector<FileFormat>& fileFormats() {
    static const std::vector<FileFormat> formats = {
        {"CSE167x scene", "CSE167x scenes", {".test"}, nullptr, true, loadCourse, nullptr},
        {"OBJ", "OBJ", {".obj"}, nullptr, true, nullptr, loadObjModel},
        {"glTF", "glTF", {".gltf", ".glb"}, gltfMagic, false, nullptr, loadGltfModel},
        {"PLY", "PLY", {".ply"}, plyMagic, false, nullptr, loadPlyModel},
        {"STL", "STL", {".stl"}, stlMagic, false, nullptr, loadStlModel},
        // FBX stays unread: docs/performance.md, "PLY and STL: Glint's readers or Assimp".
        {.name = "FBX",
         .listed = "FBX",
         .extensions = {".fbx"},
         .magic = fbxMagic,
         .hint = "export it as glTF, e.g. from Blender: File > Import > FBX, File > Export > "
                 "glTF 2.0"},
        {.name = "Blender",
         .listed = "Blender",
         .extensions = {".blend"},
         .magic = blenderMagic,
         .hint = "export it as glTF from Blender: File > Export > glTF 2.0"},
    };
    return formats;
}

FormatChoice chooseFormat(const std::string& path, std::string_view head, uint64_t size,
                          FileUse use, std::vector<Diagnostic>& warnings) {
    const std::string ext = lowerExtension(path);
    const FileFormat* named = nullptr;    // what the extension says
    const FileFormat* content = nullptr;  // what the first bytes say
    for (const FileFormat& f : fileFormats()) {
        if (!named &&
            std::find(f.extensions.begin(), f.extensions.end(), ext) != f.extensions.end())
            named = &f;
        if (!content && f.magic && f.magic(head, size)) content = &f;
    }
    const FileFormat* format = content ? content : named;
    if (!format) {
        if (!head.empty() && looksBinary(head))
            return cannotRead("Glint cannot read this file: it is binary, of no format Glint knows",
                              use);
        format = &fileFormats()[use == FileUse::Scene ? 0 : 1];  // text: a scene, or an OBJ mesh
    } else if (format->text && !head.empty() && looksBinary(head)) {
        return cannotRead("Glint cannot read this file: it is binary, and " +
                              std::string(format->name) + " files are text",
                          use);
    }
    if (!format->loadScene && !format->loadModel)
        return cannotRead("Glint cannot read " + std::string(format->name) + " files" +
                              (format->planned ? " (yet)" : "") +
                              (format->hint ? std::string(" (") + format->hint + ")" : ""),
                          use);
    if (!readsFor(*format, use))
        return cannotRead(std::string("a ") + format->name + " is not a mesh", use);
    if (content && named && content != named) {
        Diagnostic d;  // built in steps: GCC 12 warns falsely on the aggregate
        d.loc.file = path;
        d.message = std::string("the file is ") + content->name +
                    ", whatever its name says: it is read as " + content->name;
        warnings.push_back(std::move(d));
    }
    return {format, {}};
}

FormatChoice chooseFormat(const std::string& path, FileUse use, std::vector<Diagnostic>& warnings) {
    std::string head(kFileHeadBytes, '\0');
    std::ifstream in(path, std::ios::binary);
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    head.resize(in ? head.size() : static_cast<size_t>(std::max<std::streamsize>(in.gcount(), 0)));
    std::error_code ec;
    uint64_t size = std::filesystem::file_size(path, ec);
    return chooseFormat(path, head, ec ? 0 : size, use, warnings);
}

Model loadModel(const std::string& path, std::vector<Diagnostic>& warnings,
                const LoadLimits& limits) {
    FormatChoice choice = chooseFormat(path, FileUse::Model, warnings);
    if (!choice.format) throw SceneError({path, 0, 0}, choice.problem);
    LoadOptions options;
    options.limits = limits;
    return loadModelAs(*choice.format, path, warnings, options);
}

ModelScene loadModelScene(const std::string& path, std::vector<Diagnostic>& warnings, int width,
                          int height, const LoadLimits& limits, const ModelLook& look) {
    // The model is freed once placed, before the scene's BVH is built.
    return frameModelScene(loadModel(path, warnings, limits), width, height, look);
}

ModelScene loadSceneFile(const std::string& path, std::vector<Diagnostic>& warnings,
                         const LoadOptions& options) {
    FormatChoice choice = chooseFormat(path, FileUse::Scene, warnings);
    if (!choice.format) throw SceneError({path, 0, 0}, choice.problem);
    if (choice.format->loadScene) {
        const CameraChoice::Kind kind = options.camera.kind;
        if (kind != CameraChoice::Kind::First && kind != CameraChoice::Kind::Orbit)
            throw SceneError({path, 0, 0},
                             std::string("a ") + choice.format->name +
                                 " has the camera its commands define: choosing one of a file's "
                                 "cameras (--camera) is for model files");
        ModelScene out;
        out.scene = choice.format->loadScene(path, warnings, options);
        if (kind == CameraChoice::Kind::Orbit) {  // its place and field of view; the scene's lens
            CameraSpec camera = options.camera.orbit.spec();
            if (const auto& own = out.scene->camera) {
                camera.apertureRadius = own->apertureRadius;
                camera.focusDistance = own->focusDistance;
            }
            out.scene->camera = camera;
        }
        return out;
    }
    return frameModelScene(*loadModelFile(*choice.format, path, warnings, options), options.width,
                           options.height, options.look);
}

}  // namespace glint
