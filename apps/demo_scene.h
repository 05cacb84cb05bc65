#pragma once
// The built-in demo scene: scenes/demo.test, compiled into the binary (see apps/CMakeLists.txt).

#include <string_view>

namespace glint {
extern const std::string_view kDemoScene;
}
