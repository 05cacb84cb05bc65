#pragma once
/// The one place that picks a loader for a file (`glint FILE`, the scene command `mesh FILE`,
/// a model framed as a scene). A file is what its first bytes say where they say it (a binary
/// glTF, a PLY, STL, FBX or Blender file), else what its extension says, else what the caller
/// wants of it: a text file of no known extension is a CSE167x scene to `glint FILE` and an OBJ
/// mesh to `mesh FILE`. A binary file of no format Glint reads is never parsed as text.
/// Formats Glint knows but cannot read get one message naming what it reads
/// (docs/cli.md, "Which files Glint reads"). Adding a format is adding an entry to the table in
/// registry.cpp.

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "glint/core/error.h"
#include "glint/core/input_file.h"
#include "glint/scene/model.h"
#include "glint/scene/model_framing.h"
#include "glint/scene/scene.h"

namespace glint {

/// What a caller wants of a file.
enum class FileUse {
    Scene,  ///< Something to render: a scene file, or a model to frame (`glint FILE`).
    Model,  ///< Meshes to place in a scene (the course's `mesh FILE`).
};

class GltfDocument;

/// Model files read once for a sequence of frames: a glTF asset is kept parsed and posed at each
/// frame's time (io/gltf/gltf_loader.h); a model of a format without time (OBJ, PLY, STL) is
/// kept as read. Keyed by path and the options that change what is parsed.
class AssetCache {
  public:
    /// The asset cached for `key`, or null.
    std::shared_ptr<GltfDocument> find(const std::string& key) const;
    void add(const std::string& key, std::shared_ptr<GltfDocument> asset);
    /// The still model cached for `key`, or null.
    std::shared_ptr<const Model> findModel(const std::string& key) const;
    void addModel(const std::string& key, std::shared_ptr<const Model> model);

  private:
    std::vector<std::pair<std::string, std::shared_ptr<GltfDocument>>> assets_;
    std::vector<std::pair<std::string, std::shared_ptr<const Model>>> models_;
};

/// What every loader may be asked.
struct LoadOptions {
    LoadLimits limits;
    /// CSE167x scenes: unknown commands and unmatched popTransforms are warnings
    /// (CourseOptions::lenient).
    bool lenient = false;
    /// The image a model is framed for (frameModelScene): 0 x 0 for its camera's or 640 x 480.
    int width = 0, height = 0;
    /// Which of a model file's cameras to use (`--camera`). An orbit replaces any file's camera
    /// (a scene file keeps its aperture and focus); choosing one of the file's own cameras is an
    /// error for a scene file, and naming a camera is one for a model without cameras.
    CameraChoice camera;
    /// A glTF model's material variant (GltfOptions::variant); empty: its own materials.
    std::string variant;
    /// How a model is shown (frameModelScene): the studio look unless asked otherwise.
    ModelLook look;
    /// Which animation of a model file (and of the files a scene's `mesh` lines name) to play,
    /// at what time; by default none.
    ModelTime time{};
    /// Where parsed model files are kept for the next frame; null: nowhere.
    AssetCache* assets = nullptr;
};

/// A file format Glint knows, whether it reads it or not.
struct FileFormat {
    const char* name;    ///< "OBJ", "PLY": "Glint cannot read PLY files".
    const char* listed;  ///< As listed among what Glint reads: "CSE167x scenes", "OBJ".
    std::vector<std::string_view> extensions;  ///< Lower case, with the dot.
    /// Whether `head`, the first bytes of a file of `size` bytes (at most kFileHeadBytes), are
    /// this format's; null: the format has no signature.
    bool (*magic)(std::string_view head, uint64_t size) = nullptr;
    bool text = false;  ///< A text format: no binary file is one.
    /// Its loaders; both null when Glint cannot read the format.
    std::unique_ptr<Scene> (*loadScene)(const std::string& path, std::vector<Diagnostic>& warnings,
                                        const LoadOptions& options) = nullptr;
    Model (*loadModel)(const std::string& path, std::vector<Diagnostic>& warnings,
                       const LoadOptions& options) = nullptr;
    bool planned = false;  ///< Glint means to read it: its message says "(yet)".
    /// For a format Glint cannot read: how to make a file it reads of one, said in parentheses
    /// after "Glint cannot read FBX files"; null for none.
    const char* hint = nullptr;
};

/// Every format Glint knows, those it reads first.
const std::vector<FileFormat>& fileFormats();

/// Bytes of a file's beginning that decide its format (and whether it is binary).
constexpr size_t kFileHeadBytes = 4096;

/// The format to read a file as, or why there is none.
struct FormatChoice {
    const FileFormat* format = nullptr;  ///< Null: Glint cannot read the file for this use.
    /// When `format` is null, the reason, for the user ("Glint cannot read PLY files (yet); it
    /// reads CSE167x scenes (.test), OBJ (.obj) and glTF (.gltf, .glb)").
    std::string problem;
};

/// The format of the file `path` whose first bytes are `head` (at most kFileHeadBytes) of
/// `size`, for `use`. A file whose contents are of a readable format its extension does not
/// name is read as its contents say, with a warning appended to `warnings`. Reads nothing.
FormatChoice chooseFormat(const std::string& path, std::string_view head, uint64_t size,
                          FileUse use, std::vector<Diagnostic>& warnings);
/// The same, reading the file's first bytes. A file that cannot be read is chosen by its name
/// alone, so that its loader reports why.
FormatChoice chooseFormat(const std::string& path, FileUse use, std::vector<Diagnostic>& warnings);

/// Reads the model at `path` (OBJ, glTF, PLY, STL). Throws SceneError for a file of another format,
/// or as its loader does.
Model loadModel(const std::string& path, std::vector<Diagnostic>& warnings,
                const LoadLimits& limits = {});

/// Reads the model at `path` as `format` (a format that reads models) with `options`; a model of
/// a format without time is taken from options.assets when a frame before read it (a glTF
/// file is kept parsed there and posed anew).
std::shared_ptr<const Model> loadModelFile(const FileFormat& format, const std::string& path,
                                           std::vector<Diagnostic>& warnings,
                                           const LoadOptions& options);

/// Reads the model at `path` and frames it for a `width` x `height` image in `look`
/// (frameModelScene).
ModelScene loadModelScene(const std::string& path, std::vector<Diagnostic>& warnings, int width = 0,
                          int height = 0, const LoadLimits& limits = {},
                          const ModelLook& look = {});

/// What `glint FILE` renders: the scene of a scene file, or a model framed as one (its note
/// says what was assumed; empty for a scene file). Not yet prepared (Scene::prepare). Throws
/// SceneError for a file Glint cannot read, or as its loader does.
ModelScene loadSceneFile(const std::string& path, std::vector<Diagnostic>& warnings,
                         const LoadOptions& options = {});

}  // namespace glint
