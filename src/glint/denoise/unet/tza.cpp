#include "glint/denoise/unet/tza.h"

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <stdexcept>

namespace glint {
namespace {

/// Reads little-endian values from the bytes, checking each read against their end.
struct Reader {
    std::span<const uint8_t> bytes;
    size_t at = 0;
    const std::string& name;

    [[noreturn]] void fail(const std::string& why) const {
        throw std::runtime_error(name + ": not an Open Image Denoise tensor archive (" + why + ")");
    }
    void need(size_t n, const char* what) const {
        if (n > bytes.size() || at > bytes.size() - n)
            fail(std::string("it ends inside ") + what + " at byte " + std::to_string(at));
    }
    template <typename T>
    T get(const char* what) {
        need(sizeof(T), what);
        T v = 0;
        for (size_t i = 0; i < sizeof(T); ++i) v |= static_cast<T>(T(bytes[at + i]) << (8 * i));
        at += sizeof(T);
        return v;
    }
    std::string text(size_t n, const char* what) {
        need(n, what);
        std::string s(reinterpret_cast<const char*>(bytes.data() + at), n);
        at += n;
        return s;
    }
};

}  // namespace

float halfToFloat(uint16_t h) {
    const uint32_t sign = (h >> 15) & 1, exponent = (h >> 10) & 0x1f, mantissa = h & 0x3ff;
    float magnitude;
    if (exponent == 0)
        magnitude = std::ldexp(static_cast<float>(mantissa), -24);  // zero or subnormal
    else if (exponent == 31)
        magnitude = mantissa ? std::numeric_limits<float>::quiet_NaN()
                             : std::numeric_limits<float>::infinity();
    else
        magnitude =
            std::ldexp(static_cast<float>(mantissa | 0x400), static_cast<int>(exponent) - 25);
    return sign ? -magnitude : magnitude;
}

TzaTensors parseTza(std::span<const uint8_t> bytes, const std::string& name) {
    Reader r{bytes, 0, name};
    if (r.get<uint16_t>("the magic number") != 0x41D7) r.fail("its first bytes are not 0x41D7");
    const unsigned major = r.get<uint8_t>("the version"), minor = r.get<uint8_t>("the version");
    if (major != 2)
        r.fail("version " + std::to_string(major) + "." + std::to_string(minor) +
               ", where Glint reads version 2");
    const uint64_t table = r.get<uint64_t>("the table's offset");
    if (table > bytes.size()) r.fail("its table is beyond its end");
    r.at = static_cast<size_t>(table);
    const uint32_t count = r.get<uint32_t>("the table");
    TzaTensors tensors;
    for (uint32_t t = 0; t < count; ++t) {
        const uint16_t length = r.get<uint16_t>("a tensor's name");
        std::string tensorName = r.text(length, "a tensor's name");
        const unsigned ndims = r.get<uint8_t>("a tensor's shape");
        if (ndims == 0 || ndims > 4)
            r.fail("tensor '" + tensorName + "' has " + std::to_string(ndims) + " dimensions");
        TzaTensor tensor;
        uint64_t elements = 1;
        for (unsigned d = 0; d < ndims; ++d) {
            const uint32_t dim = r.get<uint32_t>("a tensor's shape");
            if (dim == 0 || dim > (1u << 20))
                r.fail("tensor '" + tensorName + "' has a dimension of " + std::to_string(dim));
            tensor.dims.push_back(static_cast<int>(dim));
            elements *= dim;
            if (elements > (uint64_t{1} << 30)) r.fail("tensor '" + tensorName + "' is too large");
        }
        tensor.layout = r.text(ndims, "a tensor's layout");
        const char type = static_cast<char>(r.get<uint8_t>("a tensor's type"));
        const uint64_t offset = r.get<uint64_t>("a tensor's offset");
        const size_t width = type == 'f' ? 4 : type == 'h' ? 2 : 0;
        if (width == 0)
            r.fail("tensor '" + tensorName + "' is of type '" + std::string(1, type) + "'");
        const uint64_t bytesNeeded = elements * width;
        if (offset > bytes.size() || bytesNeeded > bytes.size() - offset)
            r.fail("tensor '" + tensorName + "' lies beyond its end");
        tensor.values.resize(static_cast<size_t>(elements));
        const uint8_t* data = bytes.data() + offset;
        for (size_t i = 0; i < tensor.values.size(); ++i) {
            if (width == 2) {
                tensor.values[i] =
                    halfToFloat(static_cast<uint16_t>(data[2 * i] | data[2 * i + 1] << 8));
            } else {
                const uint32_t v = uint32_t(data[4 * i]) | uint32_t(data[4 * i + 1]) << 8 |
                                   uint32_t(data[4 * i + 2]) << 16 |
                                   uint32_t(data[4 * i + 3]) << 24;
                std::memcpy(&tensor.values[i], &v, sizeof v);  // (std::bit_cast: not in the
                                                               // web build's libc++)
            }
            if (!std::isfinite(tensor.values[i]))
                r.fail("tensor '" + tensorName + "' holds a value that is not finite");
        }
        if (!tensors.emplace(tensorName, std::move(tensor)).second)
            r.fail("tensor '" + tensorName + "' appears twice");
    }
    return tensors;
}

TzaTensors readTza(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot read it");
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                     std::istreambuf_iterator<char>());
    return parseTza(bytes, path);
}

}  // namespace glint
