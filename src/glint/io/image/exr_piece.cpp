#include "glint/io/image/exr_piece.h"

#include <ImfChannelList.h>
#include <ImfDoubleAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfIntAttribute.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>

#include <charconv>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "glint/core/system.h"
#include "glint/io/image/exr_streams.h"
#include "glint/scene/scene.h"

namespace glint {

namespace {

using exr_detail::MemoryInputFile;
using exr_detail::StringOStream;

/// The layout of the pixels and attributes; a reader refuses other versions. (3 added the sums'
/// rounding errors, sumErrR/G/B; 4 the squares of the albedo, passAlbedoSquaresR/G/B.)
constexpr int kPieceFormat = 4;

/// The exact channels, each double's 64 bits in two UINT channels NAME.hi and NAME.lo: the
/// beauty's sums as pairs (SampleSum: the sum, then its rounding error), then, in a piece with
/// passes, their sums (PassSums).
constexpr int kSumValues = 6, kPassValues = 14;
const char* const kExactNames[kSumValues + kPassValues] = {"sumR",
                                                           "sumG",
                                                           "sumB",
                                                           "sumErrR",
                                                           "sumErrG",
                                                           "sumErrB",
                                                           "passSquaresR",
                                                           "passSquaresG",
                                                           "passSquaresB",
                                                           "passAlbedoR",
                                                           "passAlbedoG",
                                                           "passAlbedoB",
                                                           "passNormalX",
                                                           "passNormalY",
                                                           "passNormalZ",
                                                           "passDepth",
                                                           "passHits",
                                                           "passAlbedoSquaresR",
                                                           "passAlbedoSquaresG",
                                                           "passAlbedoSquaresB"};
const char* const kWeightChannel = "weight";
const char* const kPreviewChannels[3] = {"R", "G", "B"};

/// How many exact values a pixel of `info`'s piece has.
int exactValues(const PieceInfo& info) { return kSumValues + (info.aovs.any() ? kPassValues : 0); }

/// A pixel's exact values in the order of kExactNames, `n` of them.
void getExact(const FilmSums& s, int x, int y, int n, double* out) {
    const SampleSum& sum = s.sum(x, y);
    for (int c = 0; c < 3; ++c) {
        out[c] = sum.hi[c];
        out[3 + c] = sum.lo[c];
    }
    if (n == kSumValues) return;
    const PassSums& p = s.passes(x, y);
    for (int c = 0; c < 3; ++c) {
        out[6 + c] = p.squares[c];
        out[9 + c] = p.albedo[c];
        out[12 + c] = p.normal[c];
    }
    out[15] = p.depth;
    out[16] = p.hits;
    for (int c = 0; c < 3; ++c) out[17 + c] = p.albedoSquares[c];
}

/// And back.
void setExact(FilmSums& s, int x, int y, int n, const double* in) {
    SampleSum& sum = s.sum(x, y);
    for (int c = 0; c < 3; ++c) {
        sum.hi[c] = in[c];
        sum.lo[c] = in[3 + c];
    }
    if (n == kSumValues) return;
    PassSums& p = s.passes(x, y);
    for (int c = 0; c < 3; ++c) {
        p.squares[c] = in[6 + c];
        p.albedo[c] = in[9 + c];
        p.normal[c] = in[12 + c];
    }
    p.depth = in[15];
    p.hits = in[16];
    for (int c = 0; c < 3; ++c) p.albedoSquares[c] = in[17 + c];
}

/// The UINT channel names of exact value k: NAME.hi, NAME.lo.
std::string wordChannel(int k, bool high) {
    return std::string(kExactNames[k]) + (high ? ".hi" : ".lo");
}

/// The bits of a double and back (memcpy: std::bit_cast is missing from some standard
/// libraries Glint builds with).
uint64_t bitsOf(double d) {
    uint64_t u;
    std::memcpy(&u, &d, sizeof u);
    return u;
}
double doubleOf(uint64_t u) {
    double d;
    std::memcpy(&d, &u, sizeof d);
    return d;
}

Imath::Box2i box(const PixelBounds& b) { return Imath::Box2i({b.x0, b.y0}, {b.x1 - 1, b.y1 - 1}); }

/// What a reader found wrong with a file: thrown as a PieceError naming the file.
struct Bad {
    std::string why;
};

const std::string& stringAttr(const Imf::Header& h, const char* name) {
    const auto* a = h.findTypedAttribute<Imf::StringAttribute>(name);
    if (!a) throw Bad{std::string("its header has no string attribute ") + name};
    return a->value();
}

int intAttr(const Imf::Header& h, const char* name) {
    const auto* a = h.findTypedAttribute<Imf::IntAttribute>(name);
    if (!a) throw Bad{std::string("its header has no int attribute ") + name};
    return a->value();
}

uint64_t parseU64(const std::string& text, int base, const char* name) {
    uint64_t v = 0;
    auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), v, base);
    if (text.empty() || ec != std::errc() || p != text.data() + text.size())
        throw Bad{std::string(name) + " '" + text + "' is not a number"};
    return v;
}

/// The PieceInfo a header holds, checked for consistency.
PieceInfo readInfo(const Imf::Header& h) {
    if (!h.findTypedAttribute<Imf::IntAttribute>("glint.piece"))
        throw Bad{
            "not a Glint frame piece (an OpenEXR file without the glint.piece attribute; "
            "pieces are what glint --part, --crop or --samples write)"};
    if (int format = intAttr(h, "glint.piece"); format != kPieceFormat)
        throw Bad{"piece format " + std::to_string(format) + ", but this glint reads format " +
                  std::to_string(kPieceFormat)};
    PieceInfo info;
    const Imath::Box2i display = h.displayWindow();
    const long long w = static_cast<long long>(display.max.x) - display.min.x + 1;
    const long long hh = static_cast<long long>(display.max.y) - display.min.y + 1;
    if (display.min.x != 0 || display.min.y != 0 || w < 1 || hh < 1 || w > kMaxImageSide ||
        hh > kMaxImageSide || w * hh > kMaxImagePixels)
        throw Bad{"its display window (the frame) is not a frame Glint renders"};
    info.width = static_cast<int>(w);
    info.height = static_cast<int>(hh);
    if (std::string e = parseCrop(stringAttr(h, "glint.crop"), info.crop); !e.empty())
        throw Bad{"glint.crop: " + e};
    if (info.crop.x1 > info.width || info.crop.y1 > info.height)
        throw Bad{"glint.crop " + formatCrop(info.crop) + " is outside the frame"};
    if (std::string e = parsePart(stringAttr(h, "glint.part"), info.part, info.parts); !e.empty())
        throw Bad{"glint.part: " + e};
    info.tileSize = intAttr(h, "glint.tileSize");
    if (info.tileSize < 1 || info.tileSize > kMaxImageSide)
        throw Bad{"glint.tileSize " + std::to_string(info.tileSize) + " is out of range"};
    info.spp = intAttr(h, "glint.spp");
    if (info.spp < 1 || info.spp > 65536)
        throw Bad{"glint.spp " + std::to_string(info.spp) + " is out of range"};
    const std::string& samples = stringAttr(h, "glint.samples");
    if (std::string e = parseSampleRange(samples, info.sampleBegin, info.sampleEnd); !e.empty())
        throw Bad{"glint.samples: " + e};
    if (info.sampleEnd > info.spp)
        throw Bad{"glint.samples " + samples + " goes beyond glint.spp " +
                  std::to_string(info.spp)};
    info.seed = parseU64(stringAttr(h, "glint.seed"), 10, "glint.seed");
    const std::string& hash = stringAttr(h, "glint.sceneHash");
    if (hash.size() != 16) throw Bad{"glint.sceneHash '" + hash + "' is not 16 hex digits"};
    info.sceneHash = parseU64(hash, 16, "glint.sceneHash");
    info.settings = stringAttr(h, "glint.settings");
    info.version = stringAttr(h, "glint.version");
    const auto* exposure = h.findTypedAttribute<Imf::DoubleAttribute>("glint.exposure");
    if (!exposure || !(std::abs(exposure->value()) <= 64))
        throw Bad{"glint.exposure is missing or out of range"};
    info.display.exposure = exposure->value();
    info.display.srgb = intAttr(h, "glint.srgb") != 0;
    const std::string& toneMap = stringAttr(h, "glint.toneMap");
    if (auto t = toneMapNamed(toneMap))
        info.display.toneMap = *t;
    else
        throw Bad{"glint.toneMap '" + toneMap + "' is not a tone mapper Glint has"};

    const auto* threshold = h.findTypedAttribute<Imf::DoubleAttribute>("glint.noiseThreshold");
    if (!threshold || !(threshold->value() >= 0 && threshold->value() <= 1))
        throw Bad{"glint.noiseThreshold is missing or out of range"};
    info.noiseThreshold = threshold->value();
    info.minSpp = intAttr(h, "glint.minSpp");
    if (info.noiseThreshold > 0 && (info.minSpp < 1 || info.minSpp > info.spp ||
                                    info.sampleBegin != 0 || info.sampleEnd != info.spp))
        throw Bad{"glint.minSpp or glint.samples do not fit adaptive sampling to glint.spp"};
    if (std::string aovs = stringAttr(h, "glint.aovs"); !aovs.empty())
        if (std::string e = parseAovList(aovs, info.aovs); !e.empty())
            throw Bad{"glint.aovs: " + e};

    const PixelBounds bounds = info.bounds();
    if (bounds.empty()) throw Bad{"the piece holds no pixel of the frame"};
    const Imath::Box2i data = h.dataWindow();
    if (data != box(bounds))
        throw Bad{"its data window is not the bounds of the pixels its attributes name"};
    const Imf::ChannelList& channels = h.channels();
    auto need = [&](const char* name, Imf::PixelType type) {
        const Imf::Channel* c = channels.findChannel(name);
        if (!c || c->type != type || c->xSampling != 1 || c->ySampling != 1)
            throw Bad{std::string("it has no full-size ") + (type == Imf::UINT ? "UINT" : "FLOAT") +
                      " channel " + name};
    };
    for (int k = 0; k < exactValues(info); ++k) {
        need(wordChannel(k, true).c_str(), Imf::UINT);
        need(wordChannel(k, false).c_str(), Imf::UINT);
    }
    need(kWeightChannel, Imf::UINT);
    return info;
}

/// Runs `f`, turning what OpenEXR or the checks throw into a PieceError naming `name`.
template <typename F>
auto reading(const std::string& name, F&& f) {
    try {
        return f();
    } catch (const Bad& b) {
        throw PieceError({{name, b.why}});
    } catch (const PieceError&) {
        throw;
    } catch (const std::exception& e) {
        throw PieceError({{name, std::string("not a readable OpenEXR file: ") + e.what()}});
    }
}

}  // namespace

std::string encodePiece(const PieceInfo& info, const FilmSums& sums) {
    if (sums.width() != info.width || sums.height() != info.height)
        throw RenderError("encodePiece: the sums are not the frame's size");
    const PixelBounds b = info.bounds();
    if (b.empty()) throw RenderError("the piece " + info.describe() + " holds no pixel");
    if (info.aovs.any() && !sums.hasPasses())
        throw RenderError("encodePiece: the piece carries passes, but the sums have none");
    const int w = b.x1 - b.x0, h = b.y1 - b.y0;
    const size_t n = static_cast<size_t>(w) * static_cast<size_t>(h);
    const int values = exactValues(info), words = 2 * values;
    std::vector<uint32_t> bits(n * words), weight(n);
    std::vector<float> rgb(n * 3);
    const double scale = info.display.scale();
    double exact[kSumValues + kPassValues];
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = static_cast<size_t>(y) * static_cast<size_t>(w) + x;
            if (!info.covers(b.x0 + x, b.y0 + y)) continue;  // zeros: rows of other parts
            const double wt = sums.weight(b.x0 + x, b.y0 + y);
            if (!info.allowsSamples(wt))
                throw RenderError("encodePiece: a pixel of the piece has " + std::to_string(wt) +
                                  " samples, which its samples (" + info.describe() +
                                  ") do not allow");
            weight[i] = static_cast<uint32_t>(wt);
            getExact(sums, b.x0 + x, b.y0 + y, values, exact);
            for (int k = 0; k < values; ++k) {
                const uint64_t u = bitsOf(exact[k]);
                bits[i * words + 2 * k] = static_cast<uint32_t>(u >> 32);
                bits[i * words + 2 * k + 1] = static_cast<uint32_t>(u);
            }
            const Vec3 v = pixelValue(sums.sum(b.x0 + x, b.y0 + y).value(), wt);
            for (int c = 0; c < 3; ++c) rgb[i * 3 + c] = static_cast<float>(scale * v[c]);
        }

    std::string out;
    try {
        Imf::Header header(box({0, info.width, 0, info.height}), box(b));
        header.compression() = Imf::ZIP_COMPRESSION;
        header.insert("glint.piece", Imf::IntAttribute(kPieceFormat));
        header.insert("glint.version", Imf::StringAttribute(info.version));
        header.insert("glint.crop", Imf::StringAttribute(formatCrop(info.crop)));
        header.insert("glint.part", Imf::StringAttribute(std::to_string(info.part) + "/" +
                                                         std::to_string(info.parts)));
        header.insert("glint.tileSize", Imf::IntAttribute(info.tileSize));
        header.insert("glint.samples", Imf::StringAttribute(std::to_string(info.sampleBegin) + ":" +
                                                            std::to_string(info.sampleEnd)));
        header.insert("glint.spp", Imf::IntAttribute(info.spp));
        header.insert("glint.seed", Imf::StringAttribute(std::to_string(info.seed)));
        char hash[20];
        std::snprintf(hash, sizeof hash, "%016" PRIx64, info.sceneHash);
        header.insert("glint.sceneHash", Imf::StringAttribute(hash));
        header.insert("glint.settings", Imf::StringAttribute(info.settings));
        header.insert("glint.exposure", Imf::DoubleAttribute(info.display.exposure));
        header.insert("glint.srgb", Imf::IntAttribute(info.display.srgb ? 1 : 0));
        header.insert("glint.toneMap",
                      Imf::StringAttribute(std::string(toneMapName(info.display.toneMap))));
        header.insert("glint.noiseThreshold", Imf::DoubleAttribute(info.noiseThreshold));
        header.insert("glint.minSpp", Imf::IntAttribute(info.minSpp));
        header.insert("glint.aovs", Imf::StringAttribute(aovListText(info.aovs)));

        const Imath::V2i origin(b.x0, b.y0);
        Imf::FrameBuffer frame;
        for (int c = 0; c < 3; ++c) {
            header.channels().insert(kPreviewChannels[c], Imf::Channel(Imf::FLOAT));
            frame.insert(kPreviewChannels[c],
                         Imf::Slice::Make(Imf::FLOAT, rgb.data() + c, origin, w, h,
                                          3 * sizeof(float), 3 * sizeof(float) * w));
        }
        const size_t stride = words * sizeof(uint32_t);
        for (int k = 0; k < words; ++k) {
            const std::string name = wordChannel(k / 2, k % 2 == 0);
            header.channels().insert(name, Imf::Channel(Imf::UINT));
            frame.insert(name, Imf::Slice::Make(Imf::UINT, bits.data() + k, origin, w, h, stride,
                                                stride * w));
        }
        header.channels().insert(kWeightChannel, Imf::Channel(Imf::UINT));
        frame.insert(kWeightChannel, Imf::Slice::Make(Imf::UINT, weight.data(), origin, w, h,
                                                      sizeof(uint32_t), sizeof(uint32_t) * w));
        StringOStream stream(out);
        exr_detail::useAllThreads();
        Imf::OutputFile file(stream, header);
        file.setFrameBuffer(frame);
        file.writePixels(h);
    } catch (const std::exception& e) {
        throw RenderError(std::string("EXR encoding of the piece failed: ") + e.what());
    }
    return out;
}

PieceInfo decodePieceInfo(std::string_view bytes, const std::string& name) {
    return reading(name, [&] {
        MemoryInputFile input(bytes, name);
        Imf::InputFile& file = input.file();
        return readInfo(file.header());
    });
}

PieceData decodePiece(std::string_view bytes, const std::string& name) {
    return reading(name, [&] {
        MemoryInputFile input(bytes, name);
        Imf::InputFile& file = input.file();
        PieceData piece;
        piece.info = readInfo(file.header());
        if (!file.isComplete()) throw Bad{"the file is incomplete (missing pixel data)"};
        const PixelBounds b = piece.info.bounds();
        piece.window = b;
        const int w = b.x1 - b.x0, h = b.y1 - b.y0;
        const size_t n = static_cast<size_t>(w) * static_cast<size_t>(h);
        const int values = exactValues(piece.info), words = 2 * values;
        // The reader's buffers (4 bytes a word and the weight) and the sums.
        const double need = static_cast<double>(n) * (4.0 * (words + 1) + sizeof(SampleSum) + 8 +
                                                      (values > kSumValues ? sizeof(PassSums) : 0));
        if (size_t available = availableMemoryBytes();
            available > 0 && need > static_cast<double>(available))
            throw Bad{"reading it needs " + formatBytes(need) + " of memory, more than the " +
                      formatBytes(static_cast<double>(available)) + " available"};

        std::vector<uint32_t> bits(n * words), weight(n);
        const Imath::V2i origin(b.x0, b.y0);
        const size_t stride = words * sizeof(uint32_t);
        Imf::FrameBuffer frame;
        for (int k = 0; k < words; ++k)
            frame.insert(
                wordChannel(k / 2, k % 2 == 0),
                Imf::Slice::Make(Imf::UINT, bits.data() + k, origin, w, h, stride, stride * w));
        frame.insert(kWeightChannel, Imf::Slice::Make(Imf::UINT, weight.data(), origin, w, h,
                                                      sizeof(uint32_t), sizeof(uint32_t) * w));
        file.setFrameBuffer(frame);
        file.readPixels(b.y0, b.y1 - 1);

        piece.sums = FilmSums(w, h);
        if (values > kSumValues) piece.sums.keepPasses();
        double exact[kSumValues + kPassValues];
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const size_t i = static_cast<size_t>(y) * static_cast<size_t>(w) + x;
                const bool covered = piece.info.covers(b.x0 + x, b.y0 + y);
                if (covered ? !piece.info.allowsSamples(weight[i]) : weight[i] != 0)
                    throw Bad{"pixel (" + std::to_string(b.x0 + x) + "," +
                              std::to_string(b.y0 + y) + ") holds " + std::to_string(weight[i]) +
                              " samples where the header says " +
                              (!covered ? std::string("0")
                               : piece.info.noiseThreshold > 0
                                   ? std::to_string(piece.info.minSpp) + " to " +
                                         std::to_string(piece.info.spp)
                                   : std::to_string(piece.info.samples())) +
                              ": the file is damaged"};
                for (int k = 0; k < values; ++k)
                    exact[k] = doubleOf(static_cast<uint64_t>(bits[i * words + 2 * k]) << 32 |
                                        bits[i * words + 2 * k + 1]);
                setExact(piece.sums, x, y, values, exact);
                piece.sums.weight(x, y) = weight[i];
            }
        return piece;
    });
}

}  // namespace glint
