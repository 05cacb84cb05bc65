#include "glint/core/input_log.h"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "glint/math/rng.h"

namespace glint {
namespace {

std::atomic<InputLog*> gLog{nullptr};

uint64_t load64(const char* p) {
    uint64_t v;
    std::memcpy(&v, p, sizeof v);
    return v;  // the machine's byte order; every machine Glint runs on is little-endian
}

}  // namespace

uint64_t hashBytes(std::string_view bytes, uint64_t seed) {
    // Four independent lanes over 32-byte blocks (so that the multiplications overlap), each
    // word mixed before it is folded in; then the tail, the length, and a final mix.
    constexpr uint64_t kOdd = 0x9e3779b97f4a7c15ULL;
    uint64_t lane[4] = {seed ^ 0x243f6a8885a308d3ULL, seed ^ 0x13198a2e03707344ULL,
                        seed ^ 0xa4093822299f31d0ULL, seed ^ 0x082efa98ec4e6c89ULL};
    const char* p = bytes.data();
    size_t n = bytes.size();
    for (; n >= 32; p += 32, n -= 32)
        for (int k = 0; k < 4; ++k) lane[k] = (lane[k] ^ mixBits(load64(p + 8 * k))) * kOdd;
    uint64_t h =
        mixBits(lane[0]) ^ mixBits(lane[1] + 1) ^ mixBits(lane[2] + 2) ^ mixBits(lane[3] + 3);
    for (; n >= 8; p += 8, n -= 8) h = (h ^ mixBits(load64(p))) * kOdd;
    uint64_t tail = 0;
    if (n > 0) std::memcpy(&tail, p, n);  // an empty view may hold a null pointer
    h = (h ^ mixBits(tail ^ (uint64_t{n} << 56))) * kOdd;
    return mixBits(h ^ bytes.size());
}

InputLog::InputLog() {
    InputLog* none = nullptr;
    if (!gLog.compare_exchange_strong(none, this))
        throw std::logic_error("InputLog: another log is recording");
}

InputLog::~InputLog() { gLog.store(nullptr); }

std::vector<InputRecord> InputLog::records() const {
    std::lock_guard lock(mutex_);
    return records_;
}

uint64_t InputLog::hash() const {
    std::vector<std::pair<uint64_t, uint64_t>> files;
    for (const InputRecord& r : records()) files.emplace_back(r.hash, r.bytes);
    std::sort(files.begin(), files.end());
    uint64_t h = mixBits(files.size());
    for (const auto& [fileHash, size] : files) h = mixBits(h ^ fileHash) ^ mixBits(size + h);
    return h;
}

void InputLog::record(const std::string& path, std::string_view contents) {
    InputLog* log = gLog.load();
    if (!log) return;
    InputRecord r{path, contents.size(), hashBytes(contents)};
    std::lock_guard lock(log->mutex_);
    log->records_.push_back(std::move(r));
}

}  // namespace glint
