// glint_gltf_load FILE [RUNS]: loads a glTF file RUNS times (default 5) with the glTF loader
// alone (io/gltf/gltf_loader.h: the container, tinygltf, decoding compressed meshes, checking and
// converting every accessor into MeshData; no scene, no BVH) and prints the median time of one
// load and the process's peak resident memory, for docs/performance.md ("Compressed glTF").
// The memory is that of the whole process: the mapped file, tinygltf's copy of its buffers,
// the decoders' output and working memory, and the MeshData, as they overlap in one load.

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "glint/core/error.h"
#include "glint/io/gltf/gltf_loader.h"

int main(int argc, char** argv) {
    if (argc < 2 || argc > 3) {
        std::fprintf(stderr, "usage: glint_gltf_load FILE [RUNS]\n");
        return 2;
    }
    const int runs = argc == 3 ? std::max(1, std::atoi(argv[2])) : 5;
    std::vector<double> seconds;
    size_t triangles = 0;
    for (int i = 0; i < runs; ++i) {
        std::vector<glint::Diagnostic> warnings;
        const auto start = std::chrono::steady_clock::now();
        try {
            glint::Model model = glint::loadGltf(argv[1], warnings);
            triangles = model.triangles();
        } catch (const glint::SceneError& e) {
            std::fprintf(stderr, "%s\n", e.diagnostic().format("error").c_str());
            return 1;
        }
        seconds.push_back(
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    std::sort(seconds.begin(), seconds.end());
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    std::printf("%s: %zu triangles, load %.3f s (median of %d), peak RSS %.1f MiB\n", argv[1],
                triangles, seconds[seconds.size() / 2], runs, double(usage.ru_maxrss) / 1024);
    return 0;
}
