#pragma once
// glint-mpi's first phase: every rank loads the scene itself, from the filesystem every rank
// sees (the MPI convention), and rank 0 checks that they all hold the same one before any tile
// is handed out (docs/scale-out.md, "MPI").

#include <string>
#include <vector>

#include "cli.h"

namespace glint::mpi {

/// This process's place in the job, and what rank 0 learnt of every rank while loading.
struct Job {
    int rank = 0, size = 1;
    int threads = 1;                   ///< Render threads of this rank.
    std::vector<std::string> hosts;    ///< Per rank (rank 0 only).
    std::vector<double> parseSeconds;  ///< Per rank (rank 0 only).
    std::vector<int> threadsPerRank;   ///< Per rank (rank 0 only).
    double loadBytes = 0;              ///< Bytes gathered at rank 0 for the check.

    /// "rank 2 (node7)"; the host is left out when every rank runs on one machine.
    std::string name(int r) const;
};

/// Every rank prepares the scene as `opt` asks (cli::prepare) while an InputLog records the
/// files it reads; the ranks then report to rank 0 (a gather, which no rank skips: a rank that
/// fails to load still reports), which checks that each loaded the scene, that the files'
/// hash, the image size and the samples per pixel agree, and prints the warnings once (rank
/// 0's) or every failure, naming the ranks. Returns cli::kGoOn on every rank if all is well,
/// else on every rank the exit code to end with. `assets`: where this rank keeps model files
/// for the next frame of a sequence (null: nowhere); a frame read from it hashes only the files
/// it read again, alike on every rank.
int loadEverywhere(const cli::Options& opt, cli::Prepared& prepared, Job& job,
                   AssetCache* assets = nullptr);

/// CPUs this process may run on (its affinity mask, which mpirun's binding sets), at least 1.
int availableCpus();

}  // namespace glint::mpi
