#pragma once
/// Pieces of one frame rendered apart (one command per piece, on any farm scheduler) and the
/// rules for merging them (docs/scale-out.md): which pixels and samples a piece holds, and
/// whether a set of pieces belongs to one frame and covers each pixel's samples exactly once.
/// The file format is io/image/exr_piece.h; the renderer's side is RenderOptions (crop,
/// part/parts, sampleBegin/sampleEnd).

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "glint/core/error.h"
#include "glint/render/film/display.h"
#include "glint/render/film/film.h"

namespace glint {

/// Everything that says which part of which frame a piece is.
struct PieceInfo {
    int width = 0, height = 0;  ///< The whole frame, in pixels.
    /// The pixels asked for, [x0, x1) x [y0, y1); the whole frame when no crop was asked for.
    PixelBounds crop;
    /// Of those, the rows of tiles (tileSize pixels high, counted from the frame's top) whose
    /// index % parts == part.
    int part = 0, parts = 1, tileSize = 16;
    int sampleBegin = 0, sampleEnd = 1;  ///< Samples [sampleBegin, sampleEnd) of each pixel.
    int spp = 1;                         ///< Samples per pixel of the whole frame.
    uint64_t seed = 0;
    uint64_t sceneHash = 0;  ///< InputLog::hash of the scene and everything it loaded.
    /// The options that change pixels and are not in the scene's files, as "key=value" words
    /// separated by spaces ("integrator=path maxdepth=5 ...").
    std::string settings;
    std::string version;  ///< Glint's, e.g. "1.4.0".
    /// Adaptive sampling (`--noise-threshold`): above 0, each pixel took between minSpp and spp
    /// samples, stopping on its own error (sampleBegin:sampleEnd is then 0:spp); 0: each pixel
    /// took samples() samples.
    double noiseThreshold = 0;
    int minSpp = 0;  ///< With noiseThreshold: the samples every pixel took first (<= spp).
    /// The render passes whose sums the piece carries, written by the merge beside the image.
    AovSelection aovs;
    /// How the frame is meant to be shown (the scene's defaults and the piece's command line):
    /// what `glint merge` writes with unless told otherwise. Not a pixel setting.
    DisplayTransform display;

    /// Whether the piece holds pixel (x, y) of the frame.
    bool covers(int x, int y) const {
        return crop.contains(x, y) && (parts <= 1 || (y / tileSize) % parts == part);
    }
    /// The smallest bounds around the pixels the piece holds (empty if it holds none).
    PixelBounds bounds() const;
    /// How many pixels it holds.
    long long pixelCount() const;
    int samples() const { return sampleEnd - sampleBegin; }
    /// Whether a pixel the piece holds may hold `n` samples: samples(), or with adaptive
    /// sampling minSpp to spp.
    bool allowsSamples(double n) const {
        return noiseThreshold > 0 ? n >= minSpp && n <= spp : n == samples();
    }
    /// What the piece is, for messages: "part 2/4", "crop 0,320,0,240, samples 0:32", or "the
    /// whole frame".
    std::string describe() const;
    /// The same piece of the frame (crop, part and samples).
    bool sameRegion(const PieceInfo& o) const {
        return crop == o.crop && part == o.part && parts == o.parts && tileSize == o.tileSize &&
               sampleBegin == o.sampleBegin && sampleEnd == o.sampleEnd;
    }
};

/// The order in which pieces are added: by sample range, then by part, then by crop (top to
/// bottom, left to right). Each pixel's sums are then added in the order of its samples, and
/// the merge does not depend on the order in which the files were named.
bool mergesBefore(const PieceInfo& a, const PieceInfo& b);

/// A problem with a set of pieces. `file` names the piece it is about, empty when it is about
/// none in particular (samples that no piece covers).
struct PieceProblem {
    std::string file;
    std::string message;
};

/// Pieces that cannot be merged, or a piece file that cannot be read: every problem found.
/// what() is the first one's message.
class PieceError : public RenderError {
  public:
    explicit PieceError(std::vector<PieceProblem> problems)
        : RenderError(problems.empty() ? "pieces do not merge" : problems[0].message),
          problems_(std::move(problems)) {}
    const std::vector<PieceProblem>& problems() const { return problems_; }

  private:
    std::vector<PieceProblem> problems_;
};

/// Checks that `pieces` (read from `files`, the same length) are pieces of one frame (the same
/// size, samples per pixel, seed, scene hash, settings, adaptive sampling, passes and version
/// as the first) and that, for
/// every pixel, the sample ranges of the pieces that hold it partition [0, spp): names what is
/// missing, given twice or overlapping. At most `limit` problems are returned; a last one says
/// how many more there were. Empty: the pieces merge. Memory: 8 bytes per pixel of the frame.
std::vector<PieceProblem> checkPieces(const std::vector<PieceInfo>& pieces,
                                      const std::vector<std::string>& files, size_t limit = 10);

/// "x0,x1,y0,y1", the form `--crop` takes.
std::string formatCrop(const PixelBounds& b);

// The forms `--crop`, `--part` and `--samples` take, also those of the piece files' attributes.
// Each parses the whole text (integers, no spaces) and checks only the form and the order of
// the numbers; it returns what is wrong, or an empty string.

/// "x0,x1,y0,y1" with 0 <= x0 < x1 and 0 <= y0 < y1.
std::string parseCrop(std::string_view text, PixelBounds& out);
/// "K/N" with 0 <= K < N <= kMaxParts.
std::string parsePart(std::string_view text, int& part, int& parts);
/// "A:B" with 0 <= A < B.
std::string parseSampleRange(std::string_view text, int& begin, int& end);

/// The most pieces `--part` splits a frame into.
constexpr int kMaxParts = 65536;

}  // namespace glint
