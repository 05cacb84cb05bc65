#include "glint/core/mapped_file.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>

#include "glint/core/input_log.h"

namespace glint {
namespace {

[[noreturn]] void fail(int err) { throw std::system_error(err, std::generic_category()); }

}  // namespace

MappedFile::MappedFile(const std::string& path) {
    int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) fail(errno);
    struct stat st {};
    if (::fstat(fd, &st) != 0) {
        int err = errno;
        ::close(fd);
        fail(err);
    }
    size_ = static_cast<size_t>(st.st_size);
    if (size_ == 0) {
        ::close(fd);
        InputLog::record(path, text());
        return;
    }
    void* p = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd, 0);
    if (p != MAP_FAILED) {
        ::madvise(p, size_, MADV_SEQUENTIAL);
        data_ = static_cast<const char*>(p);
        mapped_ = true;
        ::close(fd);
        InputLog::record(path, text());
        return;
    }
    // Not mappable: read it (no zero-filling of the buffer first).
    buffer_ = std::make_unique_for_overwrite<char[]>(size_);
    size_t done = 0;
    while (done < size_) {
        ssize_t n = ::read(fd, buffer_.get() + done, size_ - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            int err = n < 0 ? errno : EIO;
            ::close(fd);
            fail(err);
        }
        done += static_cast<size_t>(n);
    }
    ::close(fd);
    data_ = buffer_.get();
    InputLog::record(path, text());
}

MappedFile::~MappedFile() {
    if (mapped_) ::munmap(const_cast<char*>(data_), size_);
}

}  // namespace glint
