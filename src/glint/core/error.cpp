#include "glint/core/error.h"

namespace glint {

std::string FileLoc::str() const {
    std::string s = file;
    if (line > 0) {
        s += ':' + std::to_string(line);
        if (column > 0) s += ':' + std::to_string(column);
    }
    return s;
}

std::string Diagnostic::format(const char* kind) const {
    return loc.str() + ": " + kind + ": " + message;
}

SceneError::SceneError(FileLoc loc, std::string message)
    : std::runtime_error(Diagnostic{loc, message}.format("error")),
      diag_{std::move(loc), std::move(message)} {}

}  // namespace glint
