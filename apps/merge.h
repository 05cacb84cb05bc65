#pragma once
// glint merge -o OUT PIECE.exr...: frame pieces (apps/piece.h) merged into one image.

namespace glint::cli {

/// Runs `glint merge`: `argv[0]` is "merge", the rest its arguments. Returns the exit code:
/// 0, 1 for pieces that do not merge or cannot be read or written, 2 for usage errors.
int mergeMain(int argc, char** argv);

}  // namespace glint::cli
