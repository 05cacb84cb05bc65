// MappedFile in WebAssembly (Emscripten): the virtual file system's files are already in the
// module's memory and nothing maps them, so the file is read into a buffer.

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>

#include "glint/core/mapped_file.h"

namespace glint {

MappedFile::MappedFile(const std::string& path) {
    int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw std::system_error(errno, std::generic_category());
    struct stat st {};
    int err = ::fstat(fd, &st) != 0 ? errno : 0;
    size_ = err ? 0 : static_cast<size_t>(st.st_size);
    if (size_ > 0) buffer_.reset(new char[size_]);  // not zero-filled first
    for (size_t done = 0; !err && done < size_;) {
        ssize_t n = ::read(fd, buffer_.get() + done, size_ - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0)
            err = n < 0 ? errno : EIO;
        else
            done += static_cast<size_t>(n);
    }
    ::close(fd);
    if (err) throw std::system_error(err, std::generic_category());
    data_ = buffer_.get();
}

MappedFile::~MappedFile() {
    static_cast<void>(mapped_);  // always false here: the buffer frees itself
}

}  // namespace glint
