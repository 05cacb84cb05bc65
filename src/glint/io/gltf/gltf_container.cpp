// The glTF container before and through tinygltf: a .glb's header and chunks, the JSON's
// nesting and the memory parsing it takes, what tinygltf 2.7 leaves unchecked, and tinygltf's
// parse with Glint's file and image callbacks.

#include <algorithm>
#include <cctype>
#include <cstring>
#include <nlohmann/json.hpp>
#include <optional>
#include <system_error>

#include "glint/core/mapped_file.h"
#include "glint/core/system.h"
#include "glint/io/gltf/gltf_extensions.h"
#include "glint/io/gltf/gltf_internal.h"

namespace glint::gltf {
namespace {

/// Deepest nesting of JSON objects and arrays Glint reads. tinygltf copies `extras` and
/// `extensions` recursively: this keeps its recursion far from the stack's end.
constexpr size_t kMaxJsonDepth = 512;
/// Memory a JSON value may take once parsed by nlohmann/json and copied by tinygltf (an upper
/// bound, for the estimate made before parsing).
constexpr size_t kBytesPerJsonValue = 256;
constexpr uint32_t kGlbJson = 0x4E4F534A, kGlbBin = 0x004E4942;

/// The nesting depth of JSON text and a count of its values (an upper bound), from its
/// brackets and separators outside strings: what parsing it will cost, before it is parsed.
struct JsonShape {
    size_t depth = 0, values = 0;
};

JsonShape scanJson(std::string_view text) {
    JsonShape s;
    size_t depth = 0;
    for (size_t i = 0; i < text.size(); ++i) {
        switch (text[i]) {
            case '"':  // skip the string, escapes included
                for (++i; i < text.size() && text[i] != '"'; ++i)
                    if (text[i] == '\\') ++i;
                ++s.values;
                break;
            case '{':
            case '[':
                s.depth = std::max(s.depth, ++depth);
                ++s.values;
                break;
            case '}':
            case ']':
                depth -= depth > 0;
                break;
            case ',':
            case ':':
                ++s.values;
                break;
            default:
                break;
        }
    }
    return s;
}

/// A look at the JSON before tinygltf parses it, for what tinygltf 2.7 does not check first:
/// an image stored in a bufferView makes it form a pointer at the view's offset into its
/// buffer before checking that the offset lies in the buffer (undefined behaviour beyond it),
/// so that range is checked here (buffers hold exactly their byteLength once tinygltf has
/// read them). Returns how many buffers have no URI: in a .glb, tinygltf copies the binary
/// chunk into each. Values are read as tinygltf reads them; what tinygltf rejects is left to
/// it. The JSON is parsed only when it may hold images or use a compression extension (their
/// names, or a \u escape that might spell them) or when `countBinaryCopies`. When the
/// compression extensions need tinygltf to read other JSON (prepareCompression), `rewritten`
/// receives it.
size_t lookBeforeTinygltf(Context& ctx, std::string_view json, bool glb, bool countBinaryCopies,
                          std::string& rewritten) {
    const bool pointers = json.find("KHR_animation_pointer") != std::string_view::npos;
    if (!countBinaryCopies && json.find("\"images\"") == std::string_view::npos &&
        json.find("\\u") == std::string_view::npos && !mayUseCompression(json) && !pointers)
        return 0;
    nlohmann::json j = nlohmann::json::parse(json.begin(), json.end(), nullptr, false);
    if (!j.is_object()) return 0;
    bool changed = prepareCompression(ctx, j, glb);
    // tinygltf 2.7 drops an animation channel whose target names no node, as a
    // KHR_animation_pointer channel's does: such a target gets node -1, which tinygltf reads and
    // the animation player takes for a pointer (gltf_animations.cpp).
    if (auto animations = j.find("animations");
        pointers && animations != j.end() && animations->is_array())
        for (nlohmann::json& a : *animations)
            if (auto channels = a.find("channels"); channels != a.end() && channels->is_array())
                for (nlohmann::json& c : *channels)
                    if (auto target = c.find("target");
                        target != c.end() && target->is_object() && !target->contains("node")) {
                        (*target)["node"] = -1;
                        changed = true;
                    }
    if (changed) rewritten = j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    auto array = [&](const char* key) -> const nlohmann::json* {
        auto it = j.find(key);
        return it != j.end() && it->is_array() ? &*it : nullptr;
    };
    auto unsignedOf = [](const nlohmann::json& o, const char* key) -> std::optional<size_t> {
        auto it = o.find(key);
        if (it == o.end() || !it->is_number_unsigned()) return std::nullopt;
        return it->get<size_t>();
    };
    const nlohmann::json *buffers = array("buffers"), *views = array("bufferViews");
    size_t binaryCopies = 0;
    if (buffers)
        for (const nlohmann::json& b : *buffers)
            binaryCopies += b.is_object() && !b.contains("uri");
    const nlohmann::json* images = array("images");
    if (!images || !views || !buffers) return binaryCopies;
    for (const nlohmann::json& image : *images) {
        if (!image.is_object()) continue;
        auto v = image.find("bufferView");
        if (v == image.end() || !v->is_number_integer()) continue;
        const int view = static_cast<int>(v->get<int64_t>());  // tinygltf's conversion
        if (view < 0 || size_t(view) >= views->size() || !(*views)[size_t(view)].is_object())
            continue;  // tinygltf reports it
        const nlohmann::json& bv = (*views)[size_t(view)];
        auto b = bv.find("buffer");
        std::optional<size_t> length = unsignedOf(bv, "byteLength");
        if (b == bv.end() || !b->is_number_integer() || !length) continue;
        const int buffer = static_cast<int>(b->get<int64_t>());
        if (buffer < 0 || size_t(buffer) >= buffers->size() ||
            !(*buffers)[size_t(buffer)].is_object())
            continue;
        std::optional<size_t> size = unsignedOf((*buffers)[size_t(buffer)], "byteLength");
        const size_t offset = unsignedOf(bv, "byteOffset").value_or(0);
        if (size && (offset > *size || *length > *size - offset))
            ctx.fail("bufferView " + std::to_string(view) + ": its " + std::to_string(*length) +
                     " bytes from offset " + std::to_string(offset) +
                     " lie beyond the end of buffer " + std::to_string(buffer) + " (" +
                     std::to_string(*size) + " bytes)");
    }
    return binaryCopies;
}

uint32_t u32(std::string_view bytes, size_t at) {
    uint32_t x;
    std::memcpy(&x, bytes.data() + at, 4);
    return x;
}

/// Checks a .glb's header and chunks (tinygltf checks them too, with terser messages); returns
/// the file's bytes as its header bounds them, and sets `json` and `binBytes`.
std::string_view checkGlb(Context& ctx, std::string_view bytes, std::string_view& json,
                          size_t& binBytes) {
    if (bytes.size() < 12)
        ctx.fail(
            "the file is truncated: a binary glTF starts with a 12-byte header, the file "
            "has " +
            std::to_string(bytes.size()) + " bytes");
    if (uint32_t version = u32(bytes, 4); version != 2)
        ctx.fail("binary glTF version " + std::to_string(version) +
                 " is not supported (Glint reads version 2)");
    const size_t length = u32(bytes, 8);
    if (length > bytes.size())
        ctx.fail("the file is truncated: its header gives its length as " + std::to_string(length) +
                 " bytes, but it has " + std::to_string(bytes.size()));
    if (length < bytes.size())
        ctx.warn(std::to_string(bytes.size() - length) +
                 " bytes after the end its header gives are ignored");
    if (length < 20) ctx.fail("the file is truncated: it ends before the header of its JSON chunk");
    const size_t jsonLength = u32(bytes, 12);
    if (u32(bytes, 16) != kGlbJson) ctx.fail("its first chunk is not JSON");
    if (jsonLength > length - 20)
        ctx.fail("the file is truncated: its JSON chunk of " + std::to_string(jsonLength) +
                 " bytes does not fit in its " + std::to_string(length) + " bytes");
    json = bytes.substr(20, jsonLength);
    binBytes = 0;
    const size_t bin = 20 + jsonLength;
    if (bin < length) {
        if (length - bin < 8)
            ctx.fail("the file is truncated: the header of its binary chunk is cut off");
        binBytes = u32(bytes, bin);
        if (u32(bytes, bin + 4) == kGlbBin && binBytes > length - bin - 8)
            ctx.fail("the file is truncated: its binary chunk of " + std::to_string(binBytes) +
                     " bytes does not fit in its " + std::to_string(length) + " bytes");
    }
    return bytes.substr(0, length);
}

// tinygltf's file callbacks: files are looked for next to the glTF file only (tinygltf would
// also try the current directory), and readFile says why one cannot be read.
bool fileExists(const std::string&, void*) { return true; }

std::string expandPath(const std::string& path, void*) { return path; }

bool readFile(std::vector<unsigned char>* out, std::string*, const std::string& path, void* user) {
    Context& ctx = *static_cast<Context*>(user);
    if (!ctx.options.limits.readFiles)
        ctx.fail("buffer file '" + path + "' is not read: reading files is off");
    if (std::string problem = inputFileProblem(path); !problem.empty())
        ctx.fail("cannot read buffer file '" + path + "': " + problem);
    try {
        MappedFile file(path);
        std::string_view data = file.text();
        // Every buffer is a copy, even of a file read before: count them all.
        ctx.externalBytes += data.size();
        size_t available = memoryAvailable(ctx.options.limits);
        if (available > 0 && ctx.externalBytes > available)
            ctx.fail("its buffer files take " + formatBytes(double(ctx.externalBytes)) + " with '" +
                     path + "', more than the " + formatBytes(double(available)) +
                     " of memory available");
        out->assign(data.begin(), data.end());
    } catch (const std::system_error& e) {
        ctx.fail("cannot read buffer file '" + path + "': " + std::strerror(e.code().value()));
    }
    return true;
}

bool writeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err = "Glint does not write files while reading glTF";
    return false;
}

/// tinygltf's image callback. Images embedded in a bufferView are read later, from the range
/// Glint has checked (tinygltf passes them on unchecked); data: URIs are kept as they are
/// encoded. Only the images materials use are decoded.
bool keepImageBytes(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                    const unsigned char* bytes, int size, void*) {
    if (image->bufferView != -1) return true;
    image->image.assign(bytes, bytes + size);
    image->as_is = true;
    return true;
}

/// A .glb like `glb` (checked) with JSON chunk `json` in place of its own of `jsonLength` bytes,
/// made in `out`.
std::string_view rebuildGlb(std::string_view glb, size_t jsonLength, std::string json,
                            std::string& out) {
    json.append((4 - json.size() % 4) % 4, ' ');
    const std::string_view rest = glb.substr(20 + jsonLength);  // the binary chunk, if any
    auto u32 = [&](size_t x) {
        const uint32_t v = static_cast<uint32_t>(x);
        out.append(reinterpret_cast<const char*>(&v), 4);
    };
    out.reserve(20 + json.size() + rest.size());
    out = glb.substr(0, 8);  // magic and version
    u32(20 + json.size() + rest.size());
    u32(json.size());
    u32(kGlbJson);
    out += json;
    out += rest;
    return out;
}

/// The extensions the JSON text `json` lists in extensionsRequired (none if it does not parse).
std::vector<std::string> requiredExtensions(std::string_view json) {
    std::vector<std::string> out;
    const nlohmann::json j = nlohmann::json::parse(json.begin(), json.end(), nullptr, false);
    if (!j.is_object()) return out;
    auto it = j.find("extensionsRequired");
    if (it == j.end() || !it->is_array()) return out;
    for (const nlohmann::json& e : *it)
        if (e.is_string()) out.push_back(e.get<std::string>());
    return out;
}

/// Fails if `required` names an extension Glint does not render (gltf_extensions.h).
void checkRequiredExtensions(const Context& ctx, const std::vector<std::string>& required) {
    for (const std::string& e : required)
        if (!rendersGltfExtension(e))
            ctx.fail("the file requires extension " + e + ", which Glint does not support");
}

/// tinygltf's error text, one line.
std::string oneLine(std::string s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
    for (size_t i = 0; (i = s.find('\n', i)) != std::string::npos;) s.replace(i, 1, "; ");
    return s.empty() ? "it is not valid glTF" : s;
}

}  // namespace

void parseContainer(Context& ctx, std::string_view bytes) {
    if (bytes.empty()) ctx.fail("the file is empty");
    const bool binary = bytes.size() >= 4 && bytes.substr(0, 4) == "glTF";
    std::string_view json = bytes;
    size_t binBytes = 0;
    if (binary) bytes = checkGlb(ctx, bytes, json, binBytes);
    if (bytes.size() > UINT32_MAX) ctx.fail("the file is larger than 4 GiB");

    JsonShape shape = scanJson(json);
    if (shape.depth > kMaxJsonDepth)
        ctx.fail("its JSON nests " + std::to_string(shape.depth) + " levels deep, more than the " +
                 std::to_string(kMaxJsonDepth) + " Glint reads");
    // The JSON tree (Glint's look at it, then tinygltf's), tinygltf's copies (strings, base64
    // decoded) and of the binary chunk, once for every buffer that refers to it.
    const size_t available = memoryAvailable(ctx.options.limits);
    double needed =
        double(shape.values) * kBytesPerJsonValue + 3.0 * double(json.size()) + double(binBytes);
    auto checkMemory = [&] {
        if (available > 0 && needed > double(available))
            ctx.fail("reading it needs about " + formatBytes(needed) +
                     " of memory, more than the " + formatBytes(double(available)) + " available");
    };
    checkMemory();
    std::string rewritten, glb;
    size_t binaryCopies = lookBeforeTinygltf(ctx, json, binary, binBytes > 0, rewritten);
    if (binaryCopies > 1) {
        needed += double(binaryCopies - 1) * double(binBytes);
        checkMemory();
    }
    if (!rewritten.empty()) {  // tinygltf reads the JSON prepared for the compression extensions
        needed += double(rewritten.size()) + (binary ? double(bytes.size()) : 0);
        checkMemory();
        bytes = binary ? rebuildGlb(bytes, json.size(), rewritten, glb) : rewritten;
    }

    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks({&fileExists, &expandPath, &readFile, &writeFile, &ctx});
    loader.SetImageLoader(&keepImageBytes, nullptr);
    std::string err, warn;
    bool ok = false;
    try {
        const auto size = static_cast<unsigned int>(bytes.size());
        if (binary)
            ok = loader.LoadBinaryFromMemory(&ctx.model, &err, &warn,
                                             reinterpret_cast<const unsigned char*>(bytes.data()),
                                             size, ctx.dir);
        else
            ok = loader.LoadASCIIFromString(&ctx.model, &err, &warn, bytes.data(), size, ctx.dir);
    } catch (const SceneError&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw;
    } catch (const std::exception& e) {
        ctx.fail(std::string("tinygltf: ") + e.what());
    }
    if (!ok) {
        // What tinygltf fails on may be what an extension the file requires changes.
        checkRequiredExtensions(ctx, requiredExtensions(json));
        ctx.fail("tinygltf: " + oneLine(err));
    }
    if (!warn.empty()) ctx.warn("tinygltf: " + oneLine(warn));
    restoreCompression(ctx);
}

/// Checks the asset's version and the extensions it requires.
void checkAsset(Context& ctx) {
    const std::string& version = ctx.model.asset.version;
    if (!version.starts_with("2."))
        ctx.fail("glTF version '" + version + "' is not supported (Glint reads 2.0)");
    checkRequiredExtensions(ctx, ctx.model.extensionsRequired);
}

}  // namespace glint::gltf
