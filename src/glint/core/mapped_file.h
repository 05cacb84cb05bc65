#pragma once
/// Reading a whole file without copying it: mapped read-only into memory where the system
/// allows, read into a buffer otherwise (mapped_file.cpp natively; mapped_file_web.cpp in
/// WebAssembly, whose files are in memory already).

#include <memory>
#include <string>
#include <string_view>

namespace glint {

class MappedFile {
  public:
    /// Opens `path`. Throws std::system_error (with the system's reason) if it cannot be read.
    explicit MappedFile(const std::string& path);
    ~MappedFile();
    MappedFile(const MappedFile&) = delete;
    MappedFile& operator=(const MappedFile&) = delete;

    std::string_view text() const { return {data_, size_}; }

  private:
    const char* data_ = nullptr;
    size_t size_ = 0;
    bool mapped_ = false;
    std::unique_ptr<char[]> buffer_;
};

}  // namespace glint
