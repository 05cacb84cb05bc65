// libFuzzer harness for the OpenVDB density reader (io/vdb/vdb_reader.h), what `medium ...
// density FILE.vdb` reads.
//
// An input is a .vdb file. OpenVDB reads from a path, so each input is written to a file of this
// process's own first. Memory for the dense copy is limited to 64 MiB. A RenderError is the
// expected answer to anything that is not a readable float grid (a truncated or corrupt file, no
// such grid, too many voxels); any other exception escapes and libFuzzer reports it. A grid that
// loads must be what the reader promises: the stated size, every density finite and >= 0, a
// maximum that bounds them, and interpolated lookups anywhere in and around the box finite and
// within [0, maximum].
//
// Only Glint's side is instrumented: Debian's libopenvdb is not, so coverage guides the fuzzer
// through Glint's checks (vdb_contents.cpp) and the sanitizers see Glint's code. The seeds in
// fuzz/corpus/vdb were written with OpenVDB 10 (io::File, COMPRESS_ACTIVE_MASK, no zip, so the
// bytes are plain): tiny.vdb holds a float grid "density" of three voxels (0,0,0) = 1,
// (1,0,0) = 0.5 and (0,2,1) = 2 with a 0.25 voxel size; two.vdb a Vec3s grid "vel" and a float
// grid "heat" (background 0.1) filled with 3 over the active box (0,0,0)-(1,1,1).

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "glint/core/error.h"
#include "glint/io/vdb/vdb_module.h"

// OpenVDB's RootNode::readTopology keeps one child per origin: a corrupt file that repeats an
// origin makes it drop (and leak) the child read before. That is the library's, past Glint's
// checks (which bound what a corrupt length or count can make it allocate before the topology):
// LeakSanitizer is told to leave allocations made inside libopenvdb alone, and reports every
// other leak.
extern "C" const char* __lsan_default_suppressions() { return "leak:libopenvdb.so\n"; }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const std::string path = [] {
        std::atexit([] {
            std::remove(("/tmp/glint_fuzz_vdb." + std::to_string(getpid()) + ".vdb").c_str());
        });
        return "/tmp/glint_fuzz_vdb." + std::to_string(getpid()) + ".vdb";
    }();
    {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    }
    glint::LoadLimits limits;
    limits.memoryBytes = size_t(64) << 20;
    std::shared_ptr<const glint::DensityGrid> grid;
    try {
        grid = glint::readVdbDensity(path, "", limits);
    } catch (const glint::RenderError&) {
        return 0;
    }
    const size_t voxels = static_cast<size_t>(grid->nx) * grid->ny * grid->nz;
    if (grid->nx <= 0 || grid->ny <= 0 || grid->nz <= 0 || grid->density.size() != voxels)
        std::abort();
    const float most = grid->maxDensity();
    for (float d : grid->density)
        if (!(d >= 0 && d <= most && std::isfinite(d))) std::abort();
    // Lookups through the box and a voxel beyond it on every side, on a coarse lattice.
    for (int k = -1; k <= 8; ++k)
        for (int j = -1; j <= 8; ++j)
            for (int i = -1; i <= 8; ++i) {
                const glint::Vec3 p((grid->nx + 2) * i / 8.0 - 1, (grid->ny + 2) * j / 8.0 - 1,
                                    (grid->nz + 2) * k / 8.0 - 1);
                const double d = grid->lookup(p);
                if (!(d >= 0 && d <= most * (1 + 1e-6))) std::abort();
            }
    return 0;
}
