#pragma once
// Shared by the glTF loader's unit tests (gltf_loader_test.cpp, gltf_errors_test.cpp): test files
// in tests/data/gltf, and assets written as JSON text or .glb bytes.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "glint/io/gltf/gltf_loader.h"

namespace glint::test {

inline std::string dataPath(const std::string& name) {
    return std::string(GLINT_TEST_DATA_DIR) + "/gltf/" + name;
}

inline Model load(const std::string& name, std::vector<Diagnostic>* warningsOut = nullptr,
                      const GltfOptions& options = {}) {
    std::vector<Diagnostic> warnings;
    Model model = loadGltf(dataPath(name), warnings, options);
    if (warningsOut)
        *warningsOut = warnings;
    else
        EXPECT_TRUE(warnings.empty()) << warnings.front().format("warning");
    return model;
}

/// An asset written as JSON text: `body` (members of the top-level object, after "asset") with
/// a buffer of `data` as a data: URI when given.
inline std::string gltfText(const std::string& body, const std::string& base64 = "") {
    std::string s = R"({"asset": {"version": "2.0"})";
    if (!base64.empty())
        s += R"(, "buffers": [{"byteLength": )" + std::to_string(base64.size() / 4 * 3) +
             R"(, "uri": "data:application/octet-stream;base64,)" + base64 + "\"}]";
    if (!body.empty()) s += ", " + body;
    return s + "}";
}

/// A triangle (0,0,0) (1,0,0) (0,1,0) as 36 bytes of floats, base64.
inline const std::string kTriangle = "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA";
/// Its bufferView and accessor.
inline const std::string kTriangleViews =
    R"("bufferViews": [{"buffer": 0, "byteLength": 36}],
       "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}])";
/// The triangle as mesh 0 of node 0.
inline const std::string kTriangleScene = kTriangleViews + R"(,
       "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
       "nodes": [{"mesh": 0}])";

inline Model parse(const std::string& text, std::vector<Diagnostic>* warningsOut = nullptr,
                       const GltfOptions& options = {}) {
    std::vector<Diagnostic> warnings;
    Model model = parseGltf(text, "t.gltf", warnings, options);
    if (warningsOut)
        *warningsOut = warnings;
    else
        EXPECT_TRUE(warnings.empty()) << warnings.front().format("warning");
    return model;
}

/// The error loading `name` (a file in tests/data/gltf), or parsing `text`, gives.
inline Diagnostic errorLoading(const std::string& name) {
    std::vector<Diagnostic> warnings;
    try {
        loadGltf(dataPath(name), warnings);
    } catch (const SceneError& e) {
        return e.diagnostic();
    }
    ADD_FAILURE() << "no SceneError for " << name;
    return {};
}

inline Diagnostic errorParsing(const std::string& text, const GltfOptions& options = {}) {
    std::vector<Diagnostic> warnings;
    try {
        parseGltf(text, "t.gltf", warnings, options);
    } catch (const SceneError& e) {
        return e.diagnostic();
    }
    ADD_FAILURE() << "no SceneError for:\n" << text;
    return {};
}

/// A .glb of `json` and a binary chunk of `bin` (both padded to 4 bytes).
inline std::string glbOf(std::string json, std::string bin) {
    auto u32 = [](size_t x) {
        uint32_t v = static_cast<uint32_t>(x);
        return std::string(reinterpret_cast<const char*>(&v), 4);
    };
    json.append((4 - json.size() % 4) % 4, ' ');
    bin.append((4 - bin.size() % 4) % 4, '\0');
    return "glTF" + u32(2) + u32(12 + 8 + json.size() + 8 + bin.size()) + u32(json.size()) +
           "JSON" + json + u32(bin.size()) + std::string("BIN\0", 4) + bin;
}

}  // namespace glint::test
