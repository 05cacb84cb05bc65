// Glint's mesh and texture commands: `mesh`, `texture`, `checker` (docs/scene-format.md,
// "Meshes" and "Textures").

#include <filesystem>
#include <string>

#include "glint/io/course/course_parser.h"
#include "glint/io/image/texture_io.h"
#include "glint/io/registry.h"

namespace glint::course {

std::string Parser::scenePath(std::string_view name) const {
    std::filesystem::path p(name);
    if (p.is_absolute()) return p.string();
    return (std::filesystem::path(file_).parent_path() / p).string();
}

void Parser::cmdMesh() {
    const Transform& t = transform();  // a singular transform is reported first
    uint32_t material = builder_.materialId();
    // A model the caller holds goes by its name; a file by its path from the scene's folder.
    const bool held = models_.count(std::string(tok_[1].text)) > 0;
    if (!held && !limits_.readFiles)
        fail(1, "mesh " + quoted(1) + " is not read: reading files is off");
    std::string path = held ? std::string(tok_[1].text) : scenePath(tok_[1].text);
    auto it = models_.find(path);
    if (it == models_.end()) {
        if (std::string problem = inputFileProblem(path); !problem.empty())
            fail(1, "cannot read mesh " + quoted(1) + " (" + path + "): " + problem);
        FormatChoice format = chooseFormat(path, FileUse::Model, warnings_);
        if (!format.format) fail(0, "mesh " + quoted(1) + ": " + format.problem);
        // Errors inside the mesh file name that file (and its line and column for OBJ).
        LoadOptions options;
        options.limits = limits_;
        options.time = time_;
        options.assets = assets_;
        it = models_.emplace(path, loadModelFile(*format.format, path, warnings_, options)).first;
    }
    // Placed when the file ends (SceneBuilder::finish), so that a mesh placed several times is
    // stored once. A glTF asset's meshes are placed by its nodes, under the current transform;
    // its cameras and lights are the scene's business, and are not used.
    const std::string what = "mesh " + quoted(1);
    try {
        // Moved by a `motion`: where it puts the model at the scene's time, or over the shutter.
        std::vector<Transform> keys;
        for (const Mat4& k : movedTransforms()) {
            std::optional<Transform> moved = Transform::fromMatrix(k);
            if (!moved) fail(0, "the motion makes the transform singular or too large");
            keys.push_back(*moved);
        }
        placeModel(builder_, *it->second, keys.empty() ? t : keys.front(), material,
                   loc(tok_[0].column), what, keys.size() > 1 ? &keys : nullptr);
    } catch (const SceneError& e) {
        fail(0, what + ": " + e.diagnostic().message);
    }
}

namespace {

/// The physically based map a `texture` slot name stands for, and whether it holds colours
/// (sRGB-encoded bytes) rather than data.
struct MapSlot {
    const char* name;
    TextureSlot PbrMaterial::*slot;
    bool srgb;
};
constexpr MapSlot kMapSlots[] = {
    {"basecolormap", &PbrMaterial::baseColorTexture, true},
    {"metallicroughnessmap", &PbrMaterial::metallicRoughnessTexture, false},
    {"roughnessmap", &PbrMaterial::roughnessTexture, false},
    {"metallicmap", &PbrMaterial::metallicTexture, false},
    {"normalmap", &PbrMaterial::normalTexture, false},
    {"emissivemap", &PbrMaterial::emissiveTexture, true},
    {"transmissionmap", &PbrMaterial::transmissionTexture, false},
};

}  // namespace

void Parser::cmdMetallic() {
    double m = real(1);
    if (!(m >= 0 && m <= 1)) fail(1, "metallic must be between 0 and 1, got " + quoted(1));
    builder_.editPbr().metallic = m;
}

std::shared_ptr<const TextureImage> Parser::sceneImage(int token, bool srgb) {
    if (!limits_.readFiles)
        fail(token, "texture " + quoted(token) + " is not read: reading files is off");
    std::string path = scenePath(tok_[token].text);
    const std::string key = srgb ? path : path + "\n(linear)";
    auto it = images_.find(key);
    if (it == images_.end()) {
        try {
            it = images_.emplace(key, loadTextureImage(path, srgb, limits_)).first;
        } catch (const RenderError& e) {
            fail(token, e.what());
        }
    }
    return it->second;
}

void Parser::cmdTextureMap() {
    const MapSlot* slot = nullptr;
    for (const MapSlot& s : kMapSlots)
        if (tok_[1].text == s.name) slot = &s;
    if (tok_[2].text == "none") {
        if (ntok_ > 3)
            fail(3, "'texture " + std::string(tok_[1].text) + " none' takes no other argument");
        builder_.editPbr().*(slot->slot) = TextureSlot{};
        return;
    }
    TextureSlot t;
    if (ntok_ == 4) {
        if (tok_[3].text == "clamp")
            t.wrapS = t.wrapT = TextureWrap::Clamp;
        else if (tok_[3].text == "mirror")
            t.wrapS = t.wrapT = TextureWrap::MirroredRepeat;
        else if (tok_[3].text != "repeat")
            fail(3, "unknown texture wrap " + quoted(3) + " (repeat, clamp or mirror)");
    }
    t.image = sceneImage(2, slot->srgb);
    builder_.editPbr().*(slot->slot) = std::move(t);
}

void Parser::cmdTexture() {
    for (const MapSlot& s : kMapSlots)
        if (tok_[1].text == s.name) {
            if (ntok_ < 3)
                fail(1, "'texture " + std::string(tok_[1].text) + "' needs a file or none");
            return cmdTextureMap();
        }
    if (ntok_ > 3) fail(3, "'texture file [repeat|clamp|mirror]' takes two arguments at most");
    if (tok_[1].text == "none") {
        if (ntok_ > 2) fail(2, "'texture none' takes no other argument");
        builder_.editMaterial().texture = 0;
        return;
    }
    Texture texture;
    texture.kind = Texture::Kind::Image;
    if (ntok_ == 3) {
        if (tok_[2].text == "clamp")
            texture.wrap = TextureWrap::Clamp;
        else if (tok_[2].text == "mirror")
            texture.wrap = TextureWrap::MirroredRepeat;
        else if (tok_[2].text != "repeat")
            fail(2, "unknown texture wrap " + quoted(2) + " (repeat, clamp or mirror)");
    }
    texture.image = sceneImage(1, true);
    uint32_t id = scene().addTexture(std::move(texture));
    builder_.editMaterial().texture = id;
    imageTextures_[id] = loc(tok_[1].column);
}

void Parser::cmdChecker() {
    Texture texture;
    texture.kind = Texture::Kind::Checker;
    texture.a = colour(1);
    texture.b = colour(4);
    texture.scale = real(7);
    if (!(texture.scale > 0)) fail(7, "checker scale must be positive, got " + quoted(7));
    builder_.editMaterial().texture = scene().addTexture(std::move(texture));
}

void Parser::checkTextureCoordinates(const Scene& scene) {
    // Surfaces without coordinates show an image texture's material colour instead.
    std::map<uint32_t, size_t> without;  // texture id -> surfaces without coordinates
    auto check = [&](const Primitives& prims) {
        for (uint32_t id = 0; id < prims.size(); ++id) {
            if (prims.isInstance(id)) continue;  // its mesh is checked once, below
            uint32_t texture = scene.materials[prims.materialOf(id)].texture;
            if (texture != 0 && imageTextures_.count(texture) && !prims.hasTexCoords(id))
                ++without[texture];
        }
    };
    const Primitives& prims = scene.primitives;
    check(prims);
    for (uint32_t m = 0; m < prims.sharedMeshCount(); ++m) check(prims.sharedMesh(m));
    for (const auto& [texture, count] : without)
        warnings_.push_back(
            {imageTextures_[texture],
             "this image texture needs texture coordinates, which only meshes with 'vt' "
             "statements have: " +
                 std::to_string(count) + (count == 1 ? " surface shows" : " surfaces show") +
                 " the diffuse colour instead"});
}

}  // namespace glint::course
