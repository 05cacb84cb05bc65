#pragma once
/// An allocator for large arrays (BVH nodes and leaves, build temporaries) that asks Linux for
/// transparent huge pages: 2 MiB pages instead of 4 KiB ones mean far fewer TLB misses when
/// rays wander over tens of megabytes, and far fewer page faults when the arrays are first
/// written. Small requests, and systems without madvise, get ordinary memory.

#include <cstddef>
#include <cstdint>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace glint {

namespace detail {
constexpr size_t kHugePage = size_t{2} << 20;

inline void* allocateLarge(size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (bytes >= kHugePage) {
        size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
        // Map one huge page more than needed, so that the block can start on a 2 MiB boundary.
        size_t mapped = rounded + kHugePage;
        void* raw =
            mmap(nullptr, mapped, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (raw == MAP_FAILED) throw std::bad_alloc();
        auto base = reinterpret_cast<uintptr_t>(raw);
        uintptr_t aligned = (base + kHugePage - 1) / kHugePage * kHugePage;
        if (aligned > base) munmap(raw, aligned - base);
        size_t tail = base + mapped - (aligned + rounded);
        if (tail) munmap(reinterpret_cast<void*>(aligned + rounded), tail);
        madvise(reinterpret_cast<void*>(aligned), rounded, MADV_HUGEPAGE);
        return reinterpret_cast<void*>(aligned);
    }
#endif
    return ::operator new (bytes, std::align_val_t{64});
}

inline void freeLarge(void* p, [[maybe_unused]] size_t bytes) {  // unused without madvise
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (bytes >= kHugePage) {
        munmap(p, (bytes + kHugePage - 1) / kHugePage * kHugePage);
        return;
    }
#endif
    ::operator delete (p, std::align_val_t{64});
}
}  // namespace detail

/// std::allocator's interface over detail::allocateLarge; memory is 64-byte aligned.
template <typename T>
struct HugePageAllocator {
    using value_type = T;

    HugePageAllocator() = default;
    template <typename U>
    HugePageAllocator(const HugePageAllocator<U>&) {}

    T* allocate(size_t n) { return static_cast<T*>(detail::allocateLarge(n * sizeof(T))); }
    void deallocate(T* p, size_t n) { detail::freeLarge(p, n * sizeof(T)); }

    /// resize() default-initialises: trivial elements are left as they are, not zero-filled
    /// (huge arrays about to be overwritten should not be written twice).
    template <typename U>
    void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
        ::new (static_cast<void*>(p)) U;
    }
    template <typename U, typename... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }

    template <typename U>
    bool operator==(const HugePageAllocator<U>&) const {
        return true;
    }
};

/// A vector in huge-page memory.
template <typename T>
using LargeVector = std::vector<T, HugePageAllocator<T>>;

/// A fixed-size array in huge-page memory whose elements start uninitialised (for trivial T
/// that is about to be overwritten: no time spent zero-filling).
template <typename T>
class LargeArray {
  public:
    explicit LargeArray(size_t n)
        : n_(n), p_(n ? static_cast<T*>(detail::allocateLarge(n * sizeof(T))) : nullptr) {}
    ~LargeArray() {
        if (p_) detail::freeLarge(p_, n_ * sizeof(T));
    }
    LargeArray(const LargeArray&) = delete;
    LargeArray& operator=(const LargeArray&) = delete;

    T& operator[](size_t i) { return p_[i]; }
    const T& operator[](size_t i) const { return p_[i]; }
    T* data() { return p_; }
    size_t size() const { return n_; }

  private:
    size_t n_;
    T* p_;
};

}  // namespace glint
