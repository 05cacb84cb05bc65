#pragma once
/// The files a scene's load read, for naming and hashing a render's inputs: pieces of one frame
/// rendered on different machines, or by different MPI ranks, must come from the same scene
/// and the same meshes and textures (docs/scale-out.md). Every file a loader reads goes
/// through MappedFile, which reports it here.

#include <cstdint>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

namespace glint {

/// A 64-bit hash of `bytes` (Glint's own, not cryptographic: it tells files apart, it does not
/// resist forgery). Equal bytes give equal hashes on every machine.
uint64_t hashBytes(std::string_view bytes, uint64_t seed = 0);

struct InputRecord {
    std::string path;  ///< As the loader named it.
    uint64_t bytes = 0;
    uint64_t hash = 0;  ///< hashBytes of the contents.
};

/// While an InputLog is alive, every MappedFile opened in the process, on any thread, is
/// recorded in it. One at a time: a second one while the first lives throws std::logic_error.
class InputLog {
  public:
    InputLog();
    ~InputLog();
    InputLog(const InputLog&) = delete;
    InputLog& operator=(const InputLog&) = delete;

    /// The files read so far, in the order they were opened.
    std::vector<InputRecord> records() const;

    /// One hash of the contents of every file read: their hashes and sizes, sorted, so that it
    /// depends neither on paths (another machine mounts the files elsewhere) nor on the order
    /// in which threads opened them.
    uint64_t hash() const;

    /// Called by MappedFile for each file it opens (a no-op when no log is alive).
    static void record(const std::string& path, std::string_view contents);

  private:
    mutable std::mutex mutex_;
    std::vector<InputRecord> records_;
};

}  // namespace glint
