// parseFloat with the standard library's floating-point std::from_chars (core/parse_float.h).

#include "glint/core/parse_float.h"

namespace glint {

std::from_chars_result parseFloat(const char* first, const char* last, double& value) {
    return std::from_chars(first, last, value);
}

std::from_chars_result parseFloat(const char* first, const char* last, float& value) {
    return std::from_chars(first, last, value);
}

}  // namespace glint
