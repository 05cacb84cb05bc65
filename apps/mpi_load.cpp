#include "mpi_load.h"

#include <mpi.h>
#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>

#include "glint/core/input_log.h"
#include "glint/core/system.h"
#include "mpi_protocol.h"

namespace glint::mpi {
namespace {

/// What each rank tells rank 0 after loading; followed, in a second gather, by `textBytes` of
/// what it printed (warnings, or the error).
struct LoadStatus {
    int32_t code = cli::kGoOn;
    int32_t width = 0, height = 0, spp = 0;
    uint64_t hash = 0;
    int32_t threads = 0;
    int32_t textBytes = 0;
    double parseSeconds = 0;
    char host[64] = {};
};

/// What the process writes to stderr between start() and finish(), captured in a temporary
/// file (stderr itself when no temporary file can be made: then nothing is captured).
class StderrCapture {
  public:
    StderrCapture() {
        std::fflush(stderr);
        file_ = std::tmpfile();
        if (!file_) return;
        saved_ = ::dup(STDERR_FILENO);
        if (saved_ < 0 || ::dup2(::fileno(file_), STDERR_FILENO) < 0) {
            if (saved_ >= 0) ::close(saved_);
            std::fclose(file_);
            file_ = nullptr;
        }
    }
    ~StderrCapture() { finish(); }
    StderrCapture(const StderrCapture&) = delete;
    StderrCapture& operator=(const StderrCapture&) = delete;

    /// Restores stderr; returns what was written (at most 64 KiB of it).
    std::string finish() {
        if (!file_) return {};
        std::fflush(stderr);
        ::dup2(saved_, STDERR_FILENO);
        ::close(saved_);
        std::string text;
        std::rewind(file_);
        char buf[4096];
        for (size_t n; (n = std::fread(buf, 1, sizeof buf, file_)) > 0 && text.size() < 65536;)
            text.append(buf, n);
        std::fclose(file_);
        file_ = nullptr;
        if (text.size() > 65536) text.resize(65536);
        return text;
    }

  private:
    std::FILE* file_ = nullptr;
    int saved_ = -1;
};

/// "1", "1, 2", "1-3, 5": ranks in increasing order.
std::string rankList(const std::vector<int>& ranks) {
    std::string s;
    for (size_t i = 0; i < ranks.size();) {
        size_t j = i;
        while (j + 1 < ranks.size() && ranks[j + 1] == ranks[j] + 1) ++j;
        if (!s.empty()) s += ", ";
        s += std::to_string(ranks[i]);
        if (j > i) s += (j == i + 1 ? ", " : "-") + std::to_string(ranks[j]);
        i = j + 1;
    }
    return s;
}

/// Each line of `text` with `prefix` before it.
void printPrefixed(const std::string& prefix, const std::string& text) {
    size_t start = 0;
    while (start < text.size()) {
        size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        std::fprintf(stderr, "%s%.*s\n", prefix.c_str(), static_cast<int>(end - start),
                     text.data() + start);
        start = end + 1;
    }
}

/// Rank 0: whether every rank loaded the same scene; prints why not. Returns kGoOn or the
/// exit code.
int judge(const std::vector<LoadStatus>& all, const std::vector<std::string>& texts,
          const Job& job) {
    // Failures, grouped by what the ranks printed: ranks that failed alike are named together.
    std::map<std::string, std::vector<int>> failures;
    int code = cli::kGoOn;
    for (int r = 0; r < job.size; ++r)
        if (all[static_cast<size_t>(r)].code != cli::kGoOn) {
            failures[texts[static_cast<size_t>(r)]].push_back(r);
            if (code == cli::kGoOn) code = all[static_cast<size_t>(r)].code;
        }
    if (!failures.empty()) {
        // The common case, a mistake in the scene: every rank says the same; say it once.
        if (failures.size() == 1 && failures.begin()->second.size() == all.size()) {
            std::fputs(failures.begin()->first.c_str(), stderr);
            return code;
        }
        for (const auto& [text, ranks] : failures) {
            std::string who = ranks.size() == 1 ? job.name(ranks[0]) : "ranks " + rankList(ranks);
            std::fprintf(stderr, "glint-mpi: %s failed to load the scene:\n", who.c_str());
            printPrefixed("  ", text.empty() ? std::string("(no message)") : text);
        }
        std::fprintf(stderr, "glint-mpi: error: the scene failed to load; nothing rendered\n");
        return code;
    }
    // The same files, size and samples everywhere; ranks that differ alike are named together.
    const LoadStatus& root = all[0];
    auto describe = [](const LoadStatus& s) {
        char buf[96];
        std::snprintf(buf, sizeof buf, "input hash %016llx, %dx%d, %d spp",
                      static_cast<unsigned long long>(s.hash), s.width, s.height, s.spp);
        return std::string(buf);
    };
    std::map<std::string, std::vector<int>> differ;
    for (int r = 1; r < job.size; ++r)
        if (std::string d = describe(all[static_cast<size_t>(r)]); d != describe(root))
            differ[d].push_back(r);
    if (!differ.empty()) {
        for (const auto& [d, ranks] : differ)
            std::fprintf(
                stderr, "glint-mpi: %s loaded a different scene than rank 0: %s (rank 0: %s)\n",
                (ranks.size() == 1 ? job.name(ranks[0]) : "ranks " + rankList(ranks)).c_str(),
                d.c_str(), describe(root).c_str());
        std::fprintf(stderr,
                     "glint-mpi: error: every rank must read the same scene, meshes and textures "
                     "(a filesystem they all share); nothing rendered\n");
        return cli::kExitSceneError;
    }
    std::fputs(texts[0].c_str(), stderr);  // the warnings, once
    return cli::kGoOn;
}

}  // namespace

std::string Job::name(int r) const {
    std::string s = "rank " + std::to_string(r);
    bool oneHost = std::all_of(hosts.begin(), hosts.end(),
                               [&](const std::string& h) { return h == hosts[0]; });
    if (!oneHost && static_cast<size_t>(r) < hosts.size())
        s += " (" + hosts[static_cast<size_t>(r)] + ")";
    return s;
}

int availableCpus() {
    cpu_set_t set;
    CPU_ZERO(&set);
    if (::sched_getaffinity(0, sizeof set, &set) != 0) return 1;
    return std::max(CPU_COUNT(&set), 1);
}

int loadEverywhere(const cli::Options& opt, cli::Prepared& prepared, Job& job, AssetCache* assets) {
    LoadStatus status;
    std::string text;
    {
        InputLog log;
        StderrCapture capture;
        try {
            status.code = cli::prepare(opt, prepared, assets);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "glint: error: %s\n", e.what());
            status.code = cli::kExitSceneError;
        }
        // Rank 0 holds the image: refuse what its machine cannot hold, as glint does.
        if (status.code == cli::kGoOn && job.rank == 0) {
            const Scene& s = *prepared.scene;
            double filmBytes = static_cast<double>(s.width) * s.height * sizeof(Vec3);
            if (size_t available = availableMemoryBytes();
                available > 0 && filmBytes > static_cast<double>(available)) {
                std::fprintf(stderr,
                             "glint: error: a %dx%d image needs %s of memory, more than the %s "
                             "available\n",
                             s.width, s.height, formatBytes(filmBytes).c_str(),
                             formatBytes(static_cast<double>(available)).c_str());
                status.code = cli::kExitSceneError;
            }
        }
        text = capture.finish();
        status.hash = log.hash();
    }
    if (status.code == cli::kGoOn) {
        const Scene& s = *prepared.scene;
        status.width = s.width;
        status.height = s.height;
        status.spp = opt.spp > 0 ? opt.spp : (s.spp > 0 ? s.spp : 1);
        status.parseSeconds = prepared.parseSeconds;
    }
    status.threads = job.threads;
    status.textBytes = static_cast<int32_t>(text.size());
    std::string host = processorName();
    std::strncpy(status.host, host.c_str(), sizeof status.host - 1);

    // Everyone reports, failed or not: no rank is left waiting in a collective.
    std::vector<LoadStatus> all(job.rank == 0 ? static_cast<size_t>(job.size) : 0);
    MPI_Gather(&status, sizeof status, MPI_BYTE, all.data(), sizeof status, MPI_BYTE, 0,
               MPI_COMM_WORLD);
    std::vector<int> counts, offsets;
    std::string allText;
    if (job.rank == 0) {
        int total = 0;
        for (const LoadStatus& s : all) {
            counts.push_back(s.textBytes);
            offsets.push_back(total);
            total += s.textBytes;
        }
        allText.resize(static_cast<size_t>(total));
        job.loadBytes = static_cast<double>(sizeof status) * job.size + total;
    }
    MPI_Gatherv(text.data(), status.textBytes, MPI_CHAR, allText.data(), counts.data(),
                offsets.data(), MPI_CHAR, 0, MPI_COMM_WORLD);

    int decision = cli::kGoOn;
    if (job.rank == 0) {
        // This load's figures (a sequence loads once per frame).
        job.hosts.clear();
        job.parseSeconds.clear();
        job.threadsPerRank.clear();
        std::vector<std::string> texts;
        for (int r = 0; r < job.size; ++r) {
            const LoadStatus& s = all[static_cast<size_t>(r)];
            texts.push_back(allText.substr(static_cast<size_t>(offsets[static_cast<size_t>(r)]),
                                           static_cast<size_t>(s.textBytes)));
            job.hosts.emplace_back(s.host, strnlen(s.host, sizeof s.host));
            job.parseSeconds.push_back(s.parseSeconds);
            job.threadsPerRank.push_back(s.threads);
        }
        decision = judge(all, texts, job);
    }
    MPI_Bcast(&decision, 1, MPI_INT, 0, MPI_COMM_WORLD);
    return decision;
}

}  // namespace glint::mpi
