// Merging frame pieces (exr_piece.h): read, check, add in a fixed order.

#include <algorithm>
#include <system_error>

#include "glint/core/mapped_file.h"
#include "glint/io/image/exr_piece.h"

namespace glint {

namespace {

/// The bytes of `path`, mapped. Throws PieceError naming it.
std::unique_ptr<MappedFile> open(const std::string& path) {
    try {
        return std::make_unique<MappedFile>(path);
    } catch (const std::system_error& e) {
        throw PieceError({{path, std::string("cannot read it: ") + e.code().message()}});
    } catch (const std::exception& e) {
        throw PieceError({{path, std::string("cannot read it: ") + e.what()}});
    }
}

bool sameDisplay(const DisplayTransform& a, const DisplayTransform& b) {
    return a.exposure == b.exposure && a.srgb == b.srgb && a.toneMap == b.toneMap;
}

}  // namespace

MergedFrame mergePieceFiles(const std::vector<std::string>& paths) {
    // Every header first: problems with any file are reported together, and the coverage is
    // checked before a pixel is read.
    std::vector<PieceInfo> infos;
    std::vector<PieceProblem> problems;
    for (const std::string& path : paths) {
        try {
            infos.push_back(decodePieceInfo(open(path)->text(), path));
        } catch (const PieceError& e) {
            problems.insert(problems.end(), e.problems().begin(), e.problems().end());
        }
    }
    if (!problems.empty()) throw PieceError(std::move(problems));
    if (std::vector<PieceProblem> found = checkPieces(infos, paths); !found.empty())
        throw PieceError(std::move(found));

    std::vector<size_t> order(infos.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return mergesBefore(infos[a], infos[b]); });

    MergedFrame merged;
    merged.info = infos[order[0]];
    merged.info.crop = {0, merged.info.width, 0, merged.info.height};
    merged.info.part = 0;
    merged.info.parts = 1;
    merged.info.sampleBegin = 0;
    merged.info.sampleEnd = merged.info.spp;
    merged.sums = FilmSums(merged.info.width, merged.info.height);
    const bool passes = merged.info.aovs.any();  // the check made every piece agree
    if (passes) merged.sums.keepPasses();
    for (size_t i : order) {
        if (!sameDisplay(infos[i].display, merged.info.display))
            merged.warnings.push_back(
                {paths[i],
                 "meant to be shown with other display settings (exposure, sRGB, tone "
                 "mapper) than " +
                     paths[order[0]] + "; the merge uses " + paths[order[0]] + "'s"});
        // The pieces were checked: each pixel's pieces come in the order of their samples, the
        // first one starting at sample 0. That one's sums are copied, the others' added.
        const PieceData piece = decodePiece(open(paths[i])->text(), paths[i]);
        if (!piece.info.sameRegion(infos[i]) || piece.info.spp != infos[i].spp ||
            piece.info.sceneHash != infos[i].sceneHash)
            throw PieceError({{paths[i], "the file changed while the pieces were merged"}});
        const PixelBounds& b = piece.window;
        const bool first = piece.info.sampleBegin == 0;
        for (int y = b.y0; y < b.y1; ++y) {
            if (!piece.info.covers(b.x0, y)) continue;
            for (int x = b.x0; x < b.x1; ++x) {
                const SampleSum& s = piece.sums.sum(x - b.x0, y - b.y0);
                const double w = piece.sums.weight(x - b.x0, y - b.y0);
                if (first) {
                    merged.sums.sum(x, y) = s;
                    merged.sums.weight(x, y) = w;
                    if (passes) merged.sums.passes(x, y) = piece.sums.passes(x - b.x0, y - b.y0);
                } else {
                    merged.sums.sum(x, y).add(s);
                    merged.sums.weight(x, y) += w;
                    if (passes) merged.sums.passes(x, y) += piece.sums.passes(x - b.x0, y - b.y0);
                }
            }
        }
    }
    return merged;
}

}  // namespace glint
