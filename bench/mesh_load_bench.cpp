// glint_mesh_load_bench LOADER FILE [RUNS]: reads the mesh FILE RUNS times (default 1) with
// LOADER and prints the seconds of each read and the triangles read, for choosing between
// Glint's own PLY and STL readers and Assimp's (docs/performance.md, "PLY and STL: Glint's
// reader or Assimp"). Peak memory is measured from outside (/usr/bin/time -v, one run).
//   glint    Glint's registry and reader, to a MeshData (io/ply, io/stl): what `glint FILE`
//            reads before placing the mesh in the scene
//   assimp   Assimp's importer (Debian's libassimp 5.2.5), no post-processing, to its aiScene:
//            the least work Assimp does for a file
// A file that fails to load prints the loader's message and exits 1.

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "glint/core/error.h"
#include "glint/io/registry.h"

#if GLINT_HAVE_ASSIMP
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#endif

namespace {

/// Reads `path` with Glint; returns the triangles, or -1 with the message printed.
long long loadGlint(const std::string& path) {
    std::vector<glint::Diagnostic> warnings;
    try {
        glint::Model model = glint::loadModel(path, warnings);
        return static_cast<long long>(model.triangles());
    } catch (const glint::SceneError& e) {
        std::fprintf(stderr, "%s\n", e.diagnostic().format("error").c_str());
        return -1;
    }
}

long long loadAssimp(const std::string& path) {
#if GLINT_HAVE_ASSIMP
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(path, 0);
    if (!scene) {
        std::fprintf(stderr, "%s: assimp: %s\n", path.c_str(), importer.GetErrorString());
        return -1;
    }
    long long faces = 0;
    for (unsigned i = 0; i < scene->mNumMeshes; ++i) faces += scene->mMeshes[i]->mNumFaces;
    return faces;
#else
    std::fprintf(stderr, "%s: built without Assimp (install libassimp-dev)\n", path.c_str());
    return -1;
#endif
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3 || argc > 4) {
        std::fprintf(stderr, "usage: glint_mesh_load_bench glint|assimp FILE [RUNS]\n");
        return 2;
    }
    std::string_view loader = argv[1];
    std::string path = argv[2];
    int runs = argc == 4 ? std::atoi(argv[3]) : 1;
    if ((loader != "glint" && loader != "assimp") || runs < 1) return 2;
    for (int r = 0; r < runs; ++r) {
        auto start = std::chrono::steady_clock::now();
        long long triangles = loader == "glint" ? loadGlint(path) : loadAssimp(path);
        double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (triangles < 0) return 1;
        std::printf("%s %s: %.4f s, %lld faces\n", argv[1], path.c_str(), seconds, triangles);
    }
    return 0;
}
