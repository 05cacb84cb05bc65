#pragma once
// The command lines of glint, glint merge and glint denoise: every option, and their parsing
// with CLI11. CLI11 2.1 is header-only, and each file that includes it compiles its validators
// and parser again (about 9 s at -O3): of glint's files only options.cpp includes it. Usage
// errors exit 2.

#include <string>
#include <vector>

#include "cli.h"

namespace CLI {
class App;
}

namespace glint::cli {

/// Registers every option and flag of `glint` on `app`, storing into `opt` (glint-mpi adds its
/// own to them).
void addOptions(CLI::App& app, Options& opt);

/// Parses glint's command line (`argv[0]` the program) into `opt`. Prints the help, the version
/// or the usage error it meets. Returns kGoOn, or the exit code to end with (0 after --help).
int parseOptions(int argc, char** argv, Options& opt);

/// The command line of `glint merge -o OUT PIECE.exr...` (apps/merge.h).
struct MergeOptions {
    std::vector<std::string> pieces;
    std::string output;
    DisplayOptions shown;
    bool quiet = false;
};
/// Parses `glint merge`'s arguments (`argv[0]` is "merge") as parseOptions() does glint's.
int parseMergeOptions(int argc, char** argv, MergeOptions& opt);

/// The command line of `glint denoise IN.exr -o OUT` (apps/denoise.h).
struct DenoiseOptions {
    std::string input, output;
    std::string denoiser = "auto", quality = "balanced";
    int threads = 0;  ///< 0: all hardware threads.
    DisplayOptions shown;
    bool quiet = false;
};
/// Parses `glint denoise`'s arguments (`argv[0]` is "denoise") as parseOptions() does glint's.
int parseDenoiseOptions(int argc, char** argv, DenoiseOptions& opt);

}  // namespace glint::cli
