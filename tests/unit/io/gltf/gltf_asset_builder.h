#pragma once
// Small glTF assets written by the tests themselves: accessors of given values, each in a
// bufferView of its own, gathered in one buffer embedded as a data: URI. Used by the unit tests
// of the glTF loader and by the CLI tests.

#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

namespace glint::test {

class GltfAsset {
  public:
    static constexpr int kByte = 5120, kUbyte = 5121, kShort = 5122, kUshort = 5123;
    static constexpr int kUint = 5125, kFloat = 5126;

    /// An accessor of float `values`, elements of `type` ("SCALAR", "VEC2", "MAT4", ...).
    /// Returns its index.
    int floats(std::initializer_list<float> values, const char* type) {
        return floats(std::vector<float>(values), type);
    }
    int floats(const std::vector<float>& values, const char* type) {
        return add(values.data(), values.size(), sizeof(float), kFloat, type, false);
    }
    /// An accessor of integers stored as `componentType` (kUbyte, kUshort, kByte, kShort, kUint),
    /// `normalized` or not.
    int integers(std::initializer_list<int> values, int componentType, const char* type,
                 bool normalized = false) {
        return integers(std::vector<int>(values), componentType, type, normalized);
    }
    int integers(const std::vector<int>& values, int componentType, const char* type,
                 bool normalized = false) {
        std::string bytes;
        size_t size = componentType == kUbyte || componentType == kByte     ? 1
                      : componentType == kUshort || componentType == kShort ? 2
                                                                            : 4;
        for (int v : values) {
            uint32_t u = static_cast<uint32_t>(v);
            bytes.append(reinterpret_cast<const char*>(&u), size);  // little-endian
        }
        return add(bytes.data(), values.size(), size, componentType, type, normalized);
    }

    /// A sparse accessor of `count` float elements of `type`: zeros (or `dense`, when given)
    /// but for the elements at `indices`, which take `values`. Returns its index.
    int sparseFloats(size_t count, const char* type, const std::vector<int>& indices,
                     const std::vector<float>& values, const std::vector<float>& dense = {}) {
        std::string a = "{";
        if (!dense.empty())
            a += R"("bufferView": )" +
                 std::to_string(view(dense.data(), dense.size() * sizeof(float))) + ", ";
        std::string packed;
        for (int i : indices) {
            uint32_t u = static_cast<uint32_t>(i);
            packed.append(reinterpret_cast<const char*>(&u), 4);  // little-endian
        }
        const size_t indexView = view(packed.data(), packed.size());
        const size_t valueView = view(values.data(), values.size() * sizeof(float));
        a += R"("componentType": )" + std::to_string(kFloat) + R"(, "count": )" +
             std::to_string(count) + R"(, "type": ")" + type + R"(", "sparse": {"count": )" +
             std::to_string(indices.size()) + R"(, "indices": {"bufferView": )" +
             std::to_string(indexView) + R"(, "componentType": )" + std::to_string(kUint) +
             R"(}, "values": {"bufferView": )" + std::to_string(valueView) + "}}}";
        accessors_.push_back(a);
        return static_cast<int>(accessors_.size() - 1);
    }

    /// The asset as JSON text: `body` (members of the top-level object after "asset",
    /// "buffers", "bufferViews" and "accessors", e.g. R"("meshes": [...], "nodes": [...])").
    std::string text(const std::string& body) const {
        std::string s = R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": )" +
                        std::to_string(bin_.size()) +
                        R"(, "uri": "data:application/octet-stream;base64,)" + base64(bin_) +
                        R"("}], "bufferViews": [)";
        for (size_t i = 0; i < views_.size(); ++i) s += (i ? ", " : "") + views_[i];
        s += R"(], "accessors": [)";
        for (size_t i = 0; i < accessors_.size(); ++i) s += (i ? ", " : "") + accessors_[i];
        s += "]";
        if (!body.empty()) s += ", " + body;
        return s + "}";
    }

  private:
    static size_t componentsOf(const std::string& type) {
        if (type == "SCALAR") return 1;
        if (type == "VEC2") return 2;
        if (type == "VEC3") return 3;
        if (type == "VEC4" || type == "MAT2") return 4;
        if (type == "MAT3") return 9;
        return 16;
    }

    /// A bufferView of `bytes` bytes of `data`; returns its index.
    size_t view(const void* data, size_t bytes) {
        while (bin_.size() % 4) bin_.push_back('\0');
        const size_t offset = bin_.size();
        bin_.append(static_cast<const char*>(data), bytes);
        views_.push_back(R"({"buffer": 0, "byteOffset": )" + std::to_string(offset) +
                         R"(, "byteLength": )" + std::to_string(bytes) + "}");
        return views_.size() - 1;
    }

    int add(const void* data, size_t values, size_t size, int componentType, const char* type,
            bool normalized) {
        std::string a = R"({"bufferView": )" + std::to_string(view(data, values * size)) +
                        R"(, "componentType": )" + std::to_string(componentType) +
                        R"(, "count": )" + std::to_string(values / componentsOf(type)) +
                        R"(, "type": ")" + type + "\"";
        if (normalized) a += R"(, "normalized": true)";
        accessors_.push_back(a + "}");
        return static_cast<int>(accessors_.size() - 1);
    }

    static std::string base64(const std::string& in) {
        static const char* kDigits =
            "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        std::string out;
        for (size_t i = 0; i < in.size(); i += 3) {
            uint32_t n = static_cast<uint32_t>(static_cast<unsigned char>(in[i])) << 16;
            if (i + 1 < in.size())
                n |= static_cast<uint32_t>(static_cast<unsigned char>(in[i + 1])) << 8;
            if (i + 2 < in.size()) n |= static_cast<unsigned char>(in[i + 2]);
            out += kDigits[n >> 18 & 63];
            out += kDigits[n >> 12 & 63];
            out += i + 1 < in.size() ? kDigits[n >> 6 & 63] : '=';
            out += i + 2 < in.size() ? kDigits[n & 63] : '=';
        }
        return out;
    }

    std::string bin_;
    std::vector<std::string> views_, accessors_;
};

}  // namespace glint::test
