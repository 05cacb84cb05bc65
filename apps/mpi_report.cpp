#include "mpi_report.h"

#include <algorithm>
#include <cstdio>
#include <vector>

#include "cli.h"
#include "glint/core/atomic_file.h"
#include "mpi_protocol.h"

namespace glint::mpi {
namespace {

/// The p-th quantile (0 to 1) of `v`, by the nearest rank; 0 if empty.
double quantile(std::vector<double> v, double p) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    size_t i = static_cast<size_t>(p * static_cast<double>(v.size() - 1) + 0.5);
    return v[std::min(i, v.size() - 1)];
}

std::string number(double d) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", d);
    return buf;
}

/// "1234 bytes", "56.7 kB", "8.9 MB" (decimal units: the bytes are exact figures).
std::string bytes(double b) {
    char buf[32];
    if (b < 1e4)
        std::snprintf(buf, sizeof buf, "%.0f bytes", b);
    else if (b < 1e7)
        std::snprintf(buf, sizeof buf, "%.1f kB", b / 1e3);
    else
        std::snprintf(buf, sizeof buf, "%.1f MB", b / 1e6);
    return buf;
}

std::string list(const std::vector<double>& v) {
    std::string s = "[";
    for (size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + number(v[i]);
    return s + "]";
}

}  // namespace

void printMpiStats(const Scene& scene, double parseSeconds, const RankWork& work, const Job& job,
                   const FrameFigures& figures, double writeSeconds) {
    RenderResult r;
    r.rays = figures.rays;
    r.seconds = figures.seconds;
    cli::printStats(scene, parseSeconds, work.buildSeconds, r, writeSeconds);
    std::vector<int> perRank(static_cast<size_t>(job.size), 0);
    std::vector<double> times;
    for (const TileTime& t : figures.tileTimes) {
        ++perRank[static_cast<size_t>(t.rank)];
        times.push_back(t.seconds);
    }
    int allThreads = 0;
    for (int t : job.threadsPerRank) allThreads += t;
    std::printf("MPI         %s, %d threads in all; %s of %dx%d pixels\n",
                cli::count(static_cast<unsigned long long>(job.size), "rank", "ranks").c_str(),
                allThreads,
                cli::count(static_cast<unsigned long long>(figures.tiles), "tile", "tiles").c_str(),
                work.tileSide, work.tileSide);
    std::printf("Tiles       per rank");
    for (int k = 0; k < job.size; ++k) std::printf(" %d", perRank[static_cast<size_t>(k)]);
    std::printf("; render time per tile: median %.4f s, max %.4f s\n", quantile(times, 0.5),
                quantile(times, 1));
    std::printf("Messages    %s to rank 0, %s from it, %s for the load check\n",
                bytes(figures.bytesToRoot).c_str(), bytes(figures.bytesFromRoot).c_str(),
                bytes(job.loadBytes).c_str());
    double build = *std::max_element(figures.buildSeconds.begin(), figures.buildSeconds.end());
    double parse = *std::max_element(job.parseSeconds.begin(), job.parseSeconds.end());
    std::printf("Slowest     parse %.3f s, build %.3f s (of every rank)\n", parse, build);
    std::printf("Coordinator %.3f s CPU on rank 0's MPI thread (%.2f%% of the render time)\n",
                figures.coordinatorCpuSeconds,
                figures.seconds > 0 ? 100 * figures.coordinatorCpuSeconds / figures.seconds : 0);
}

void writeTimings(const std::string& path, const Scene& scene, const RankWork& work, const Job& job,
                  const FrameFigures& figures, double writeSeconds) {
    std::string s = "{\n";
    s += "  \"ranks\": " + std::to_string(job.size) + ",\n";
    s += "  \"threads\": " +
         list(std::vector<double>(job.threadsPerRank.begin(), job.threadsPerRank.end())) + ",\n";
    s += "  \"width\": " + std::to_string(scene.width) + ",\n";
    s += "  \"height\": " + std::to_string(scene.height) + ",\n";
    s += "  \"spp\": " + std::to_string(work.options.spp) + ",\n";
    s += "  \"tile_side\": " + std::to_string(work.tileSide) + ",\n";
    s += "  \"parse_seconds\": " + list(job.parseSeconds) + ",\n";
    s += "  \"build_seconds\": " + list(figures.buildSeconds) + ",\n";
    s += "  \"render_seconds\": " + number(figures.seconds) + ",\n";
    s += "  \"write_seconds\": " + number(writeSeconds) + ",\n";
    s += "  \"coordinator_cpu_seconds\": " + number(figures.coordinatorCpuSeconds) + ",\n";
    s += "  \"receive_seconds\": " + number(figures.receiveSeconds) + ",\n";
    s += "  \"bytes_to_root\": " + number(figures.bytesToRoot) + ",\n";
    s += "  \"bytes_from_root\": " + number(figures.bytesFromRoot) + ",\n";
    s += "  \"load_check_bytes\": " + number(job.loadBytes) + ",\n";
    s += "  \"rays\": " + number(static_cast<double>(figures.rays.total())) + ",\n";
    s += "  \"tile_fields\": [\"x0\", \"y0\", \"width\", \"height\", \"rank\", \"seconds\"],\n";
    s += "  \"tiles\": [\n";
    for (size_t i = 0; i < figures.tileTimes.size(); ++i) {
        const TileTime& t = figures.tileTimes[i];
        s += "    [" + std::to_string(t.bounds.x0) + ", " + std::to_string(t.bounds.y0) + ", " +
             std::to_string(t.bounds.x1 - t.bounds.x0) + ", " +
             std::to_string(t.bounds.y1 - t.bounds.y0) + ", " + std::to_string(t.rank) + ", " +
             number(t.seconds) + "]" + (i + 1 < figures.tileTimes.size() ? ",\n" : "\n");
    }
    s += "  ]\n}\n";
    writeFileAtomically(path, s);
}

}  // namespace glint::mpi
