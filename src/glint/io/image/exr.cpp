#include "glint/io/image/exr.h"

#include <Iex.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string_view>
#include <utility>
#include <vector>

#include "glint/core/error.h"
#include "glint/core/system.h"
#include "glint/io/image/exr_streams.h"
#include "glint/scene/scene.h"

namespace glint {

namespace {

using exr_detail::MemoryInputFile;
using exr_detail::StringOStream;

}  // namespace

namespace exr_detail {

namespace {

constexpr size_t npos = std::string_view::npos;

/// The null ending a name (of an attribute, its type or a channel) that starts at `at`, or npos
/// where OpenEXR refuses it: it reads at most 255 characters and the null.
size_t nameEnd(std::string_view bytes, size_t at) {
    const size_t end = bytes.find('\0', at);
    return end == npos || end - at > 255 ? npos : end;
}

/// Where OpenEXR 3.1 stops reading a value of `type` that starts at `at` and claims `size` bytes
/// (the readValueFrom of each attribute type), or npos where OpenEXR refuses the value first.
size_t valueEnd(std::string_view bytes, std::string_view type, size_t at, size_t size) {
    // clang-format off
    static constexpr std::pair<std::string_view, size_t> kFixedSize[] = {
        {"box2f", 16}, {"box2i", 16}, {"chromaticities", 32}, {"compression", 1},
        {"deepImageState", 1}, {"double", 8}, {"envmap", 1}, {"float", 4}, {"int", 4},
        {"keycode", 28}, {"lineOrder", 1}, {"m33d", 72}, {"m33f", 36}, {"m44d", 128},
        {"m44f", 64}, {"rational", 8}, {"tiledesc", 9}, {"timecode", 8}, {"v2d", 16},
        {"v2f", 8}, {"v2i", 8}, {"v3d", 24}, {"v3f", 12}, {"v3i", 12}};
    // clang-format on
    for (auto [name, n] : kFixedSize)
        if (type == name) return at + n;
    if (type == "chlist") {  // channels up to an empty name, each a name and 16 bytes
        size_t i = at;
        while (i < bytes.size() && bytes[i] != 0) {
            const size_t name = nameEnd(bytes, i);
            if (name == npos) return npos;
            i = name + 1 + 16;
        }
        return i + 1;
    }
    if (type == "floatvector") return at + size / 4 * 4;
    if (type == "idmanifest") return size < 4 ? npos : at + 8 + (size - 4);
    return at + size;  // string, stringvector, preview and types OpenEXR keeps opaque
}

}  // namespace

void checkAttributeSizes(std::string_view bytes) {
    auto int32At = [&](size_t at) {
        uint32_t v = 0;
        for (int k = 3; k >= 0; --k) v = v << 8 | static_cast<unsigned char>(bytes[at + k]);
        return static_cast<int32_t>(v);
    };
    if (bytes.size() < 8) return;
    const bool multipart = (int32At(4) & 0x1000) != 0;
    size_t i = 8;
    for (;;) {                                       // headers
        while (i < bytes.size() && bytes[i] != 0) {  // attributes: name, type, size, value
            const size_t name = nameEnd(bytes, i);
            const size_t type = name == npos ? npos : nameEnd(bytes, name + 1);
            if (type == npos || type + 5 > bytes.size()) return;
            const int32_t size = int32At(type + 1);
            const size_t value = type + 5;
            if (size < 0 || static_cast<size_t>(size) > bytes.size() - value)
                throw Iex::InputExc("attribute '" + std::string(bytes.substr(i, name - i)) +
                                    "' claims " + std::to_string(size) +
                                    " bytes, more than the file holds");
            i = valueEnd(bytes, bytes.substr(name + 1, type - name - 1), value,
                         static_cast<size_t>(size));
            if (i == npos) return;
        }
        // A header ends with a null byte; a multi-part file's headers end with an empty one.
        if (!multipart || i + 1 >= bytes.size() || bytes[i + 1] == 0) return;
        ++i;
    }
}

}  // namespace exr_detail

namespace {

/// The layers of the render passes: each pass's channel names, in the order written.
struct PassLayer {
    const char* channels[3];
    int count;
};
constexpr PassLayer kAlbedo{{"albedo.R", "albedo.G", "albedo.B"}, 3};
constexpr PassLayer kNormal{{"normal.X", "normal.Y", "normal.Z"}, 3};
constexpr PassLayer kDepth{{"depth.Z", nullptr, nullptr}, 1};
constexpr PassLayer kVariance{{"variance.R", "variance.G", "variance.B"}, 3};
// Written with the variance when the albedo is written too: for the denoiser.
constexpr PassLayer kAlbedoVariance{{"albedoVariance.R", "albedoVariance.G", "albedoVariance.B"},
                                    3};

}  // namespace

std::string encodeExr(const Film& film, double scale, const RenderPasses* aovs,
                      AovSelection which) {
    const int w = film.width(), h = film.height();
    const size_t n = static_cast<size_t>(w) * h;
    if (aovs && !aovs->empty() && (aovs->width != w || aovs->height != h))
        throw RenderError("EXR encoding failed: the passes are not the image's size");
    if (!aovs || aovs->empty()) which = {};
    // Channel planes, row by row: doubles beyond the float range become +-inf here (IEEE
    // conversion), as in PFM output.
    std::vector<std::pair<const char*, std::vector<float>>> planes;
    auto plane = [&](const char* name, auto value) {
        std::vector<float> v(n);
        for (size_t i = 0; i < n; ++i) v[i] = static_cast<float>(value(i));
        planes.emplace_back(name, std::move(v));
    };
    const char* rgb[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c)
        plane(rgb[c], [&](size_t i) { return scale * film.pixels()[i][c]; });
    auto layer = [&](const PassLayer& l, const std::vector<Vec3>& values, double k) {
        for (int c = 0; c < l.count; ++c)
            plane(l.channels[c], [&](size_t i) { return k * values[i][c]; });
    };
    if (which.albedo) layer(kAlbedo, aovs->albedo, 1);
    if (which.normal) layer(kNormal, aovs->normal, 1);
    if (which.depth) plane(kDepth.channels[0], [&](size_t i) { return aovs->depth[i]; });
    if (which.variance) layer(kVariance, aovs->variance, scale * scale);
    if (which.variance && which.albedo && aovs->albedoVariance.size() == n)
        layer(kAlbedoVariance, aovs->albedoVariance, 1);

    std::string out;
    try {
        Imf::Header header(w, h);
        header.compression() = Imf::ZIP_COMPRESSION;
        Imf::FrameBuffer frame;
        for (auto& [name, values] : planes) {
            header.channels().insert(name, Imf::Channel(Imf::FLOAT));
            frame.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(values.data()),
                                          sizeof(float), sizeof(float) * w));
        }
        StringOStream stream(out);
        exr_detail::useAllThreads();
        Imf::OutputFile file(stream, header);
        file.setFrameBuffer(frame);
        file.writePixels(h);
    } catch (const std::exception& e) {
        throw RenderError(std::string("EXR encoding failed: ") + e.what());
    }
    return out;
}

std::pair<long long, long long> exrImageSize(std::string_view bytes, const std::string& name) {
    try {
        MemoryInputFile input(bytes, name);
        Imf::InputFile& file = input.file();
        const Imath::Box2i window = file.header().dataWindow();
        return {static_cast<long long>(window.max.x) - window.min.x + 1,
                static_cast<long long>(window.max.y) - window.min.y + 1};
    } catch (const std::exception& e) {
        throw RenderError("cannot read image '" + name + "': " + e.what());
    }
}

namespace {

/// Rows converted per batch when reading: bounds the float buffer whatever the image size.
constexpr int kRowsPerBatch = 64;

/// Reads the channels `names` (a null or absent name is skipped) of the file in `bytes`,
/// full-size, after checking the image's size against Glint's limits and the memory for
/// `bytesPerPixel` of output (and `passBytesPerPixel` more when any name from the fourth on is
/// there: the render passes): calls start(width, height, present) with which names are
/// there, then batch(y0, rows, planes) for each band of at most kRowsPerBatch rows, planes[c]
/// holding channel c's rows (row by row; empty for a channel not there).
template <typename Start, typename Batch>
void readChannels(std::string_view bytes, const std::string& name,
                  const std::vector<const char*>& names, double bytesPerPixel,
                  double passBytesPerPixel, Start&& start, Batch&& batch) {
    auto fail = [&](const std::string& why) -> RenderError {
        return RenderError("cannot read image '" + name + "': " + why);
    };
    MemoryInputFile input(bytes, name);
    Imf::InputFile& file = input.file();
    if (!file.isComplete()) throw fail("the file is incomplete (missing pixel data)");
    const Imf::Header& header = file.header();
    const Imath::Box2i window = header.dataWindow();
    const long long w = static_cast<long long>(window.max.x) - window.min.x + 1;
    const long long h = static_cast<long long>(window.max.y) - window.min.y + 1;
    if (w < 1 || h < 1 || w > kMaxImageSide || h > kMaxImageSide || w * h > kMaxImagePixels)
        throw fail("the image size " + std::to_string(w) + "x" + std::to_string(h) +
                   " is beyond Glint's limits");
    const Imf::ChannelList& channels = header.channels();
    std::vector<bool> present(names.size());
    for (size_t c = 0; c < names.size(); ++c) {
        const Imf::Channel* ch = names[c] ? channels.findChannel(names[c]) : nullptr;
        if (ch && (ch->xSampling != 1 || ch->ySampling != 1))
            throw fail(std::string("channel ") + names[c] +
                       " is subsampled; Glint reads full-size channels only");
        present[c] = ch != nullptr;
    }
    bool passes = false;
    for (size_t c = 3; c < names.size(); ++c) passes = passes || present[c];
    const double bytesNeeded =
        static_cast<double>(w * h) * (bytesPerPixel + (passes ? passBytesPerPixel : 0));
    if (size_t available = availableMemoryBytes();
        available > 0 && bytesNeeded > static_cast<double>(available))
        throw fail("a " + std::to_string(w) + "x" + std::to_string(h) + " image needs " +
                   formatBytes(bytesNeeded) + " of memory, more than the " +
                   formatBytes(static_cast<double>(available)) + " available");
    const int width = static_cast<int>(w), height = static_cast<int>(h);
    start(width, height, present);
    std::vector<std::vector<float>> planes(names.size());
    for (size_t c = 0; c < names.size(); ++c)
        if (present[c]) planes[c].resize(static_cast<size_t>(width) * kRowsPerBatch);
    for (int y0 = 0; y0 < height; y0 += kRowsPerBatch) {
        const int count = std::min(kRowsPerBatch, height - y0);
        Imf::FrameBuffer frame;
        for (size_t c = 0; c < names.size(); ++c)
            if (present[c])
                frame.insert(names[c],
                             Imf::Slice::Make(Imf::FLOAT, planes[c].data(),
                                              Imath::V2i(window.min.x, window.min.y + y0), width,
                                              count, sizeof(float), sizeof(float) * width));
        file.setFrameBuffer(frame);
        file.readPixels(window.min.y + y0, window.min.y + y0 + count - 1);
        batch(y0, count, planes);
    }
}

/// R, G and B, else Y (for all three); throws if neither is there.
std::vector<const char*> colourChannels(std::string_view bytes, const std::string& name) {
    MemoryInputFile input(bytes, name);
    const Imf::ChannelList& channels = input.file().header().channels();
    if (channels.findChannel("R") && channels.findChannel("G") && channels.findChannel("B"))
        return {"R", "G", "B"};
    if (channels.findChannel("Y")) return {"Y", nullptr, nullptr};
    throw RenderError("cannot read image '" + name + "': no R, G, B or Y channels");
}

template <typename F>
auto decoding(const std::string& name, F&& f) {
    try {
        return f();
    } catch (const RenderError&) {
        throw;
    } catch (const std::exception& e) {
        throw RenderError("cannot read image '" + name + "': " + e.what());
    }
}

}  // namespace

Film decodeExr(std::string_view bytes, const std::string& name) {
    return decodeExrLayers(bytes, name).color;
}

ExrLayers decodeExrLayers(std::string_view bytes, const std::string& name) {
    return decoding(name, [&] {
        std::vector<const char*> names = colourChannels(bytes, name);
        for (const PassLayer* l : {&kAlbedo, &kNormal, &kDepth, &kVariance, &kAlbedoVariance})
            for (int c = 0; c < 3; ++c) names.push_back(c < l->count ? l->channels[c] : nullptr);
        ExrLayers out;
        RenderPasses& p = out.aovs;
        int width = 0;
        // A layer counts when all its channels are there: albedo, normal, depth, variance,
        // albedoVariance.
        auto layerOf = [](size_t channel) { return (static_cast<int>(channel) - 3) / 3; };
        bool has[5] = {true, true, true, true, true};
        auto start = [&](int w, int h, const std::vector<bool>& present) {
            width = w;
            out.color = Film(w, h);
            for (size_t c = 3; c < names.size(); ++c)
                if (names[c] && !present[c]) has[layerOf(c)] = false;
            out.found = {has[0], has[1], has[2], has[3]};
            const size_t n = static_cast<size_t>(w) * static_cast<size_t>(h);
            p.width = w;
            p.height = h;
            if (has[0]) p.albedo.resize(n);
            if (has[1]) p.normal.resize(n);
            if (has[2]) p.depth.resize(n);
            if (has[3]) p.variance.resize(n);
            if (has[4]) p.albedoVariance.resize(n);
        };
        auto batch = [&](int y0, int rows, const std::vector<std::vector<float>>& planes) {
            const bool grey = planes[1].empty();
            const size_t count = static_cast<size_t>(width) * rows;
            const size_t first = static_cast<size_t>(y0) * width;
            for (size_t k = 0; k < count; ++k) {
                const int x = static_cast<int>(k % width), y = y0 + static_cast<int>(k / width);
                out.color.at(x, y) =
                    grey ? Vec3(planes[0][k]) : Vec3(planes[0][k], planes[1][k], planes[2][k]);
            }
            auto fill = [&](int layer, std::vector<Vec3>& to) {
                if (!has[layer]) return;
                const size_t f = 3 + 3 * static_cast<size_t>(layer);
                for (size_t k = 0; k < count; ++k)
                    to[first + k] = Vec3(planes[f][k], planes[f + 1][k], planes[f + 2][k]);
            };
            if (!out.found.any()) return;
            fill(0, p.albedo);
            fill(1, p.normal);
            fill(3, p.variance);
            fill(4, p.albedoVariance);
            if (has[2])
                for (size_t k = 0; k < count; ++k) p.depth[first + k] = planes[9][k];
        };
        // The film, and the passes' 104 bytes a pixel where the file has them.
        readChannels(bytes, name, names, sizeof(Vec3), 104, start, batch);
        return out;
    });
}

}  // namespace glint
