// glint_sheen_albedo_table [OUTPUT]: computes the table of the Charlie sheen's directional
// albedo E(mu, alpha) of src/glint/render/bsdfs/sheen.h (its layout is there) and writes it as C++ to
// OUTPUT (standard output without one):
//
//   build/tools/glint_sheen_albedo_table src/glint/render/bsdfs/tables/sheen_albedo_table.cpp
//   clang-format -i src/glint/render/bsdfs/tables/sheen_albedo_table.cpp
//
// Run it when sheen.h's lobe or the table's layout changes; the unit tests recompute every entry
// and fail when the committed table no longer matches. It takes about half a second.

#include <cstdio>

#include "glint/render/bsdfs/sheen.h"

int main(int argc, char** argv) {
    using namespace glint::sheen_albedo_table;
    std::FILE* out = argc > 1 ? std::fopen(argv[1], "w") : stdout;
    if (!out) {
        std::perror(argv[1]);
        return 1;
    }
    std::fprintf(out,
                 "// Written by tools/sheen_albedo_table.cpp: the Charlie sheen's directional "
                 "albedo\n// (src/glint/render/bsdfs/sheen.h, sheen_albedo_table). Do not edit.\n\n"
                 "#include \"glint/render/bsdfs/sheen.h\"\n\nnamespace glint::sheen_albedo_table {\n\n"
                 "const float kE[kRows * kColumns] = {\n");
    for (int r = 0; r < kRows; ++r) {
        std::fprintf(out, "    // row %d: alpha %.6g\n   ", r, rowAlpha(r));
        for (int c = 0; c < kColumns; ++c) {
            const float e = static_cast<float>(
                glint::sheenAlbedoByQuadrature(rowAlpha(r), columnMu(c), kSteps));
            std::fprintf(out, " %.9gf,%s", static_cast<double>(e),
                         (c % 6 == 5 && c + 1 < kColumns) ? "\n   " : "");
        }
        std::fprintf(out, "\n");
    }
    std::fprintf(out, "};\n\n}  // namespace glint::sheen_albedo_table\n");
    if (out != stdout) std::fclose(out);
    return 0;
}
