#include "glint/core/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "glint/core/error.h"

namespace glint {

namespace {
std::atomic<const char*> pending{nullptr};

/// Publishes the temporary's name while it exists.
struct Pending {
    explicit Pending(const std::string& tmp) { pending.store(tmp.c_str()); }
    ~Pending() { pending.store(nullptr); }
};
}  // namespace

const char* pendingTempFile() { return pending.load(); }

void writeFileAtomically(const std::string& path, std::string_view bytes) {
    static std::atomic<unsigned> counter{0};
    std::string tmp = path + ".glint-tmp-" + std::to_string(::getpid()) + "-" +
                      std::to_string(counter.fetch_add(1));
    auto fail = [&](const char* what, int err) {
        throw RenderError("cannot write '" + path + "': " + what + ": " + std::strerror(err));
    };

    Pending published(tmp);
    int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) fail("cannot create file", errno);
    const char* p = bytes.data();
    size_t left = bytes.size();
    while (left > 0) {
        ssize_t n = ::write(fd, p, left);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            int err = n < 0 ? errno : EIO;
            ::close(fd);
            ::unlink(tmp.c_str());
            fail("write failed", err);
        }
        p += n;
        left -= static_cast<size_t>(n);
    }
    if (::fsync(fd) != 0 || ::close(fd) != 0) {
        int err = errno;
        ::unlink(tmp.c_str());
        fail("write failed", err);
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        int err = errno;
        ::unlink(tmp.c_str());
        fail("cannot replace file", err);
    }
}

}  // namespace glint
