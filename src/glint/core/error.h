#pragma once
/// Errors and warnings that point at a place in a scene file.

#include <stdexcept>
#include <string>

namespace glint {

/// A position in an input file; line and column are 1-based, 0 when unknown.
struct FileLoc {
    std::string file;
    int line = 0;
    int column = 0;

    /// "file:line:col", or less when line or column are unknown.
    std::string str() const;
};

/// A message tied to a file position, printed as "file:line:col: <kind>: message".
struct Diagnostic {
    FileLoc loc;
    std::string message;

    std::string format(const char* kind) const;
};

/// Thrown for malformed or unusable input. The message names the place in the file.
class SceneError : public std::runtime_error {
  public:
    SceneError(FileLoc loc, std::string message);
    const Diagnostic& diagnostic() const { return diag_; }

  private:
    Diagnostic diag_;
};

/// Thrown when rendering or writing output fails for reasons other than the scene itself.
class RenderError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

}  // namespace glint
