#pragma once
// glint --crop, --samples, --part: rendering one piece of a frame to an OpenEXR piece file
// for `glint merge` (docs/scale-out.md).

#include <cstdint>
#include <string>

#include "cli.h"
#include "glint/render/film/piece.h"
#include "glint/render/renderer.h"

namespace glint::cli {

/// Whether the options ask for a piece (--crop, --samples or --part).
bool wantsPiece(const Options& opt);

/// The checks that need no scene: a piece goes to `-o FILE.exr`, is reproducible (no --time),
/// adaptive only when split by pixels (not --samples), and raw (no --denoise). Returns kGoOn, or
/// the exit code of the usage error it printed.
int checkPieceOptions(const Options& opt);

/// The piece the options ask for of the prepared scene, rendered at `spp` samples per pixel
/// from a scene whose inputs hash to `sceneHash`. Checks the bounds against the frame (usage
/// errors). Returns kGoOn, or the exit code of the error it printed.
int describePiece(const Options& opt, const Prepared& prepared, int spp, uint64_t sceneHash,
                  PieceInfo& out);

/// Sets the render options that render `piece` (and keep its sums).
void renderPieceWith(const PieceInfo& piece, RenderOptions& ro);

/// The options that change pixels without being in the scene's files, for PieceInfo::settings.
std::string pixelSettings(const Options& opt, const Scene& scene);

}  // namespace glint::cli
