#pragma once
// What glint-mpi's rank 0 reports of a frame: --stats (glint's, and the job's) and --timings
// (JSON for the scaling model, bench/mpi_model.py).

#include <string>

#include "mpi_load.h"
#include "mpi_render.h"

namespace glint::mpi {

/// glint's --stats (every rank's rays), then the job: ranks, tiles per rank, bytes sent, tile
/// times, and the CPU time of rank 0's MPI thread.
void printMpiStats(const Scene& scene, double parseSeconds, const RankWork& work, const Job& job,
                   const FrameFigures& figures, double writeSeconds);

/// Writes the figures to `path` as JSON, atomically. Throws RenderError.
void writeTimings(const std::string& path, const Scene& scene, const RankWork& work, const Job& job,
                  const FrameFigures& figures, double writeSeconds);

}  // namespace glint::mpi
