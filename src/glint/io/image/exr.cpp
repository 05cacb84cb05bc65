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

/// Rows converted per batch when reading: bounds the float buffer whatever the image size.
constexpr int kRowsPerBatch = 64;

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

std::string encodeExr(const Film& film, double scale) {
    const int w = film.width(), h = film.height();
    // Doubles beyond the float range become +-inf here (IEEE conversion), as in PFM output.
    std::vector<float> rgb(static_cast<size_t>(w) * h * 3);
    size_t i = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const Vec3& c = film.at(x, y);
            rgb[i++] = static_cast<float>(scale * c.x);
            rgb[i++] = static_cast<float>(scale * c.y);
            rgb[i++] = static_cast<float>(scale * c.z);
        }

    std::string out;
    try {
        Imf::Header header(w, h);
        header.compression() = Imf::ZIP_COMPRESSION;
        const char* names[3] = {"R", "G", "B"};
        Imf::FrameBuffer frame;
        for (int c = 0; c < 3; ++c) {
            header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
            frame.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(rgb.data() + c),
                                              3 * sizeof(float), 3 * sizeof(float) * w));
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

Film decodeExr(std::string_view bytes, const std::string& name) {
    auto fail = [&](const std::string& why) -> RenderError {
        return RenderError("cannot read image '" + name + "': " + why);
    };
    try {
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
        const double filmBytes = static_cast<double>(w * h) * sizeof(Vec3);
        if (size_t available = availableMemoryBytes();
            available > 0 && filmBytes > static_cast<double>(available))
            throw fail("a " + std::to_string(w) + "x" + std::to_string(h) + " image needs " +
                       formatBytes(filmBytes) + " of memory, more than the " +
                       formatBytes(static_cast<double>(available)) + " available");

        // R, G and B, else Y for all three.
        const Imf::ChannelList& channels = header.channels();
        std::vector<const char*> names;
        if (channels.findChannel("R") && channels.findChannel("G") && channels.findChannel("B"))
            names = {"R", "G", "B"};
        else if (channels.findChannel("Y"))
            names = {"Y"};
        else
            throw fail("no R, G, B or Y channels");
        for (const char* n : names)
            if (const Imf::Channel* ch = channels.findChannel(n);
                ch->xSampling != 1 || ch->ySampling != 1)
                throw fail(std::string("channel ") + n +
                           " is subsampled; Glint reads full-size channels only");

        const int width = static_cast<int>(w), height = static_cast<int>(h);
        const size_t n = names.size();
        Film film(width, height);
        std::vector<float> rows(static_cast<size_t>(width) * n * kRowsPerBatch);
        for (int y0 = 0; y0 < height; y0 += kRowsPerBatch) {
            const int count = std::min(kRowsPerBatch, height - y0);
            Imf::FrameBuffer frame;
            for (size_t c = 0; c < n; ++c)
                frame.insert(names[c],
                             Imf::Slice::Make(Imf::FLOAT, rows.data() + c,
                                              Imath::V2i(window.min.x, window.min.y + y0), width,
                                              count, n * sizeof(float), n * sizeof(float) * width));
            file.setFrameBuffer(frame);
            file.readPixels(window.min.y + y0, window.min.y + y0 + count - 1);
            const float* p = rows.data();
            for (int y = y0; y < y0 + count; ++y)
                for (int x = 0; x < width; ++x, p += n)
                    film.at(x, y) = n == 3 ? Vec3(p[0], p[1], p[2]) : Vec3(p[0]);
        }
        return film;
    } catch (const RenderError&) {
        throw;
    } catch (const std::exception& e) {
        throw fail(e.what());
    }
}

}  // namespace glint
