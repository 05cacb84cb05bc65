#include "glint/scene/model.h"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <utility>

namespace glint {

CameraChoice CameraChoice::parse(const std::string& text) {
    CameraChoice c;
    if (text.empty()) return c;
    if (text == "none") {
        c.kind = Kind::None;
        return c;
    }
    if (std::all_of(text.begin(), text.end(), [](char ch) { return ch >= '0' && ch <= '9'; })) {
        c.kind = Kind::Index;
        auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), c.index);
        if (ec != std::errc()) c.index = SIZE_MAX;  // beyond any file's cameras
        return c;
    }
    c.kind = Kind::Name;
    c.name = text;
    return c;
}

std::string CameraChoice::describe() const {
    switch (kind) {
        case Kind::Index:
            return "camera " + std::to_string(index);
        case Kind::Name:
            return "camera '" + name + "'";
        case Kind::None:
            return "no camera";
        default:
            return "the first camera";
    }
}

size_t Model::triangles() const {
    size_t n = 0;
    for (const ModelPlacement& p : placements) n += meshes[p.mesh].triangles.size();
    return n;
}

Model singleMeshModel(MeshData mesh) {
    Model model;
    model.name = mesh.name;
    model.meshes.push_back(std::move(mesh));
    model.placements.push_back({0, Transform(), 0});
    return model;
}

void placeModel(SceneBuilder& builder, const Model& model, const Transform& worldFromModel,
                uint32_t defaultMaterial, const FileLoc& where, const std::string& what) {
    // Placements at the model's origin take the scene's transform as it is: the transform an
    // OBJ file is placed by is exactly the scene's.
    const bool identity = worldFromModel.isIdentity();
    for (const ModelPlacement& p : model.placements) {
        std::optional<Transform> t =
            identity ? p.worldFromObject
            : p.worldFromObject.isIdentity()
                ? worldFromModel
                : Transform::fromMatrix(worldFromModel.matrix() * p.worldFromObject.matrix());
        if (!t)
            throw SceneError({model.name, 0, 0},
                             "node " + std::to_string(p.node) +
                                 ": its transform, with the scene's, is singular or too large");
        builder.placeMesh(model.meshes[p.mesh], *t, defaultMaterial, where, what);
    }
}

}  // namespace glint
