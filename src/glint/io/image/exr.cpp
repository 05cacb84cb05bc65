#include "glint/io/image/exr.h"

#include <Iex.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include "glint/core/error.h"
#include "glint/core/system.h"
#include "glint/io/image/exr_streams.h"
#include "glint/scene/scene.h"

namespace glint {

namespace {

using exr_detail::MemoryIStream;
using exr_detail::StringOStream;

/// Rows converted per batch when reading: bounds the float buffer whatever the image size.
constexpr int kRowsPerBatch = 64;

}  // namespace

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
        exr_detail::checkAttributeSizes(bytes);
        MemoryIStream stream(bytes, name);
        Imf::InputFile file(stream, 0);  // one thread: see exr_detail::useAllThreads
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
        exr_detail::checkAttributeSizes(bytes);
        MemoryIStream stream(bytes, name);
        Imf::InputFile file(stream, 0);  // one thread: see exr_detail::useAllThreads
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
