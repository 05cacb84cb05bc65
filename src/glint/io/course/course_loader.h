#pragma once
/// Loader for the CSE167x homework 3 scene format and Glint's extensions to it
/// (docs/scene-format.md has every command, its defaults and the errors it reports).

#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "glint/core/error.h"
#include "glint/core/input_file.h"
#include "glint/scene/model.h"
#include "glint/scene/scene.h"

namespace glint {

struct CourseOptions {
    /// Memory, and whether the files a scene names (`mesh`, `texture`) may be read.
    LoadLimits limits;
    /// Lenient, as the course's own parser was: an unknown command is skipped and a
    /// popTransform without a pushTransform is ignored, each with a warning (one per command
    /// name, with a count), instead of being an error.
    bool lenient = false;
    /// The animation its `mesh` files play, at what time (LoadOptions::time); and where they
    /// are kept for the next frame (null: nowhere).
    ModelTime time{};
    class AssetCache* assets = nullptr;
    /// Models the caller holds, by the name a `mesh` line gives them in place of a file (the
    /// Python module's meshes made of arrays, docs/python.md): placed as a mesh file's would be.
    std::map<std::string, std::shared_ptr<const Model>> models{};
};

/// Parses `text`, naming `fileName` in diagnostics. Throws SceneError at the first error, or if
/// the scene would need more memory than `options.limits` allow; appends warnings to
/// `warnings`. The scene is not yet prepared (see Scene::prepare).
std::unique_ptr<Scene> parseCourseScene(std::string_view text, const std::string& fileName,
                                        std::vector<Diagnostic>& warnings,
                                        const CourseOptions& options = {});

/// Reads and parses the file at `path`. Throws SceneError if it cannot be read or is malformed.
std::unique_ptr<Scene> loadCourseScene(const std::string& path, std::vector<Diagnostic>& warnings,
                                       const CourseOptions& options = {});

/// Every command name the loader accepts.
std::vector<std::string_view> courseCommandNames();

}  // namespace glint
