#include "mpi_protocol.h"

#include <algorithm>

namespace glint::mpi {

std::vector<PixelBounds> frameTiles(int width, int height, int side) {
    std::vector<PixelBounds> tiles;
    for (int y0 = 0; y0 < height; y0 += side)
        for (int x0 = 0; x0 < width; x0 += side)
            tiles.push_back({x0, std::min(x0 + side, width), y0, std::min(y0 + side, height)});
    return tiles;
}

std::string processorName() {
    char name[MPI_MAX_PROCESSOR_NAME] = {};
    int length = 0;
    if (MPI_Get_processor_name(name, &length) != MPI_SUCCESS) return "?";
    return std::string(name, static_cast<size_t>(std::max(length, 0)));
}

}  // namespace glint::mpi
