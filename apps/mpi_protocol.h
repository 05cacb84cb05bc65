#pragma once
// glint-mpi's messages (docs/scale-out.md, "MPI"): what rank 0 (the coordinator, which renders
// too) and the other ranks (workers) send each other while they render a frame in tiles.
//
// Every rank runs the same binary on machines of one architecture (the MPI convention for one
// program), so messages are plain structs sent as bytes; the pixels are doubles, exactly the
// values the renderer computed.

#include <mpi.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "glint/render/film/film.h"
#include "glint/render/integrators/integrator.h"

namespace glint::mpi {

/// Message tags: one per direction, so that each direction's messages arrive in the order they
/// were sent (MPI's non-overtaking rule, for one sender, tag and communicator).
constexpr int kTagToRoot = 1;
constexpr int kTagToWorker = 2;

/// The side of a tile, in pixels, by default (--tile): the unit of work rank 0 hands out. Small
/// enough for thousands of them in a 4K frame (load balance), large enough that a message (24 kB
/// of pixels) costs little next to rendering it (docs/scale-out.md).
constexpr int kTileSide = 32;

/// The tiles of a width x height image, `side` pixels square (clipped at the right and bottom
/// edges), in rows from the top-left corner: every pixel in exactly one.
std::vector<PixelBounds> frameTiles(int width, int height, int side);

/// What a worker sends rank 0.
enum class ToRoot : int32_t {
    Request = 1,  ///< Ready: send me `count` tiles. `seconds`: its BVH build time.
    Result = 2,   ///< Tile `tile`'s pixels follow (3 doubles each, rows from the top); it also
                  ///< asks for one more tile. `seconds`: its render time; `rays`: its counts.
    Error = 3,    ///< The text that follows says what failed; the rank renders no more.
    Done = 4,     ///< Answers Stop: the rank has stopped and will send nothing more.
};

struct ToRootHeader {
    ToRoot type = ToRoot::Request;
    int32_t tile = -1;
    int32_t count = 0;
    int32_t reserved = 0;
    double seconds = 0;
    uint64_t rays[4] = {};  ///< RayCounts: camera, shadow, reflection, nonFinite.
};

/// What rank 0 sends a worker.
enum class ToWorker : int32_t {
    Assign = 1,  ///< Render tile `tile`, pixels `bounds`.
    Stop = 2,    ///< No more tiles (or a rank failed): stop, cancel what is in hand, send Done.
};

struct ToWorkerMessage {
    ToWorker type = ToWorker::Assign;
    int32_t tile = -1;
    PixelBounds bounds;
};

inline void packRays(const RayCounts& r, uint64_t out[4]) {
    out[0] = r.camera;
    out[1] = r.shadow;
    out[2] = r.reflection;
    out[3] = r.nonFinite;
}

inline RayCounts unpackRays(const uint64_t in[4]) {
    RayCounts r;
    r.camera = in[0];
    r.shadow = in[1];
    r.reflection = in[2];
    r.nonFinite = in[3];
    return r;
}

/// A message to rank 0: the header, then `payload` bytes (pixels or text).
inline std::vector<char> packToRoot(const ToRootHeader& h, const void* payload = nullptr,
                                    size_t bytes = 0) {
    std::vector<char> m(sizeof h + bytes);
    std::memcpy(m.data(), &h, sizeof h);
    if (bytes) std::memcpy(m.data() + sizeof h, payload, bytes);
    return m;
}

/// The name of this machine as MPI knows it.
std::string processorName();

}  // namespace glint::mpi
