#pragma once
/// Frame pieces as OpenEXR files (docs/scale-out.md, "Frame pieces"): what `glint --part`,
/// `--crop` and `--samples` write and `glint merge` reads.
///
/// The display window is the whole frame, the data window the piece's bounding pixels. Each
/// pixel holds the exact sums the merge adds, each double's 64 bits in two UINT channels
/// (sumR.hi, sumR.lo, and G and B likewise: no float type holds a double losslessly), its
/// sample count in the UINT channel `weight` (0 for pixels of the window the piece does not
/// hold; with adaptive sampling each pixel's own), and R, G, B as 32-bit floats (the piece's
/// own average, times 2^exposure) so that any EXR viewer shows it. A piece rendered with
/// `--aov` also holds the sums behind the passes (PassSums) the same way: passSquaresR/G/B,
/// passAlbedoR/G/B, passNormalX/Y/Z, passDepth, passHits. ZIP compressed. The header's glint.*
/// attributes hold the PieceInfo (format 2: glint.noiseThreshold, glint.minSpp and glint.aovs
/// were added to format 1).

#include <string>
#include <string_view>

#include "glint/render/film/film.h"
#include "glint/render/film/piece.h"

namespace glint {

/// A piece as read from its file.
struct PieceData {
    PieceInfo info;
    /// The piece's bounding pixels in the frame, info.bounds(): `sums` is this size, its (0, 0)
    /// the window's top-left pixel.
    PixelBounds window;
    FilmSums sums;
};

/// Encodes the pixels of `sums` (the whole frame's size, as RenderResult::sums) that `info`
/// covers. Throws RenderError if the piece holds no pixel or the sizes differ.
std::string encodePiece(const PieceInfo& info, const FilmSums& sums);

/// The PieceInfo in the header of the piece file held in `bytes`, checked for consistency (no
/// pixel is decoded). `name` is for messages. Throws PieceError, one problem naming `name`, for
/// a malformed, truncated or foreign file.
PieceInfo decodePieceInfo(std::string_view bytes, const std::string& name);

/// The whole piece. Also checks that each pixel's sample count is what the header says (the
/// piece's samples where it covers the frame, 0 elsewhere). Throws PieceError as above.
PieceData decodePiece(std::string_view bytes, const std::string& name);

/// The frame merged from piece files, and what it is.
struct MergedFrame {
    PieceInfo info;  ///< The first piece's, in merge order (settings, display, ...).
    FilmSums sums;   ///< The whole frame; resolve() gives the image.
    std::vector<PieceProblem> warnings;  ///< E.g. pieces meant to be shown differently.
};

/// Reads the piece files at `paths`, checks that they are the pieces of one frame and cover
/// every pixel's samples exactly once (checkPieces), then adds them in merge order
/// (mergesBefore): each pixel's first piece is copied, the later ones added, so pieces that
/// hold whole pixels give each pixel exactly the single render's sums. Throws PieceError with
/// every problem found (unreadable files first, then the check's).
MergedFrame mergePieceFiles(const std::vector<std::string>& paths);

}  // namespace glint
