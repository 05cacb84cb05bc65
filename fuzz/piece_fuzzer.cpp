// libFuzzer harness for the frame-piece reader (io/image/exr_piece.h), what `glint merge` reads.
//
// An input is an OpenEXR file. A PieceError is the expected answer to anything that is not a
// well-formed piece; any other exception escapes and libFuzzer reports it. A piece that decodes
// must be consistent: its window the bounds of its pixels, each pixel's sample count the
// header's (the reader checks), and re-encoding it must give a piece that decodes to the same
// sums.

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string_view>

#include "glint/io/image/exr_piece.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    glint::PieceData piece;
    try {
        piece = glint::decodePiece(bytes, "fuzz.exr");
    } catch (const glint::PieceError&) {
        return 0;
    }
    const glint::PixelBounds& w = piece.window;
    if (!(w == piece.info.bounds()) || piece.sums.width() != w.x1 - w.x0 ||
        piece.sums.height() != w.y1 - w.y0)
        std::abort();
    // Back to a frame-sized FilmSums (bounded: the reader's limits), encoded and read again.
    if (static_cast<long long>(piece.info.width) * piece.info.height > (1 << 20)) return 0;
    glint::FilmSums frame(piece.info.width, piece.info.height);
    // A piece with render passes (since format 2, `--aov`) carries their sums too.
    const bool passes = piece.info.aovs.any() && piece.sums.hasPasses();
    if (piece.info.aovs.any() && !passes) std::abort();
    if (passes) frame.keepPasses();
    for (int y = w.y0; y < w.y1; ++y)
        for (int x = w.x0; x < w.x1; ++x) {
            frame.sum(x, y) = piece.sums.sum(x - w.x0, y - w.y0);
            frame.weight(x, y) = piece.sums.weight(x - w.x0, y - w.y0);
            if (passes) frame.passes(x, y) = piece.sums.passes(x - w.x0, y - w.y0);
        }
    const glint::PieceData again =
        glint::decodePiece(glint::encodePiece(piece.info, frame), "again.exr");
    for (int y = 0; y < w.y1 - w.y0; ++y)
        for (int x = 0; x < w.x1 - w.x0; ++x)
            if (std::memcmp(&again.sums.sum(x, y), &piece.sums.sum(x, y),
                            sizeof(glint::SampleSum)) != 0)
                std::abort();
    return 0;
}
