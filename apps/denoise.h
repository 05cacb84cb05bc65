#pragma once
// glint denoise IN.exr -o OUT: a saved render denoised with the render passes its file holds
// (glint --aov all, or a merge of such pieces), as Open Image Denoise's oidnDenoise does.

namespace glint::cli {

/// Runs `glint denoise`: `argv[0]` is "denoise", the rest its arguments. Returns the exit code:
/// 0, 1 for a file that cannot be read or written, 2 for usage errors.
int denoiseMain(int argc, char** argv);

}  // namespace glint::cli
