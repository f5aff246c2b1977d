// The allocation hooks that make memguard::AllocationBudget bite. Compiled into each Lodestone
// executable (not into a shared library: a replacement operator new must come before
// libstdc++'s in the dynamic linker's lookup order, and only the executable is sure to).
//
// - The global operator new / new[] (plain, nothrow, aligned) are replaced, as the standard
//   allows: each charges the thread's budget, then takes the memory from malloc /
//   aligned_alloc; the matching deletes free it.
// - mrpt::aligned_malloc / aligned_calloc (libmrpt-core, exported, called from the other MRPT
//   libraries through the PLT) are interposed with the same behaviour plus the charge: MRPT
//   memsets a block aligned_calloc returned null for, so a refusal must throw, not return null.
//   Their contract - size rounded up to a multiple of the alignment, aligned_alloc, freed by
//   aligned_free's ::free - is MRPT 2.5's, kept as is.
// With no budget active, charge() is one thread-local read: the cost of a normal program.
#include <lodestone/memguard/AllocationBudget.h>

#include <cstdlib>
#include <cstring>
#include <new>

namespace {
using lodestone::memguard::charge;

void* allocate(std::size_t n) {
    if (!charge(n)) throw std::bad_alloc();
    for (;;) {
        if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
        std::new_handler handler = std::get_new_handler();
        if (!handler) throw std::bad_alloc();
        handler();
    }
}

void* allocateAligned(std::size_t n, std::size_t alignment) {
    if (!charge(n)) throw std::bad_alloc();
    if (alignment < sizeof(void*)) alignment = sizeof(void*);
    const std::size_t rounded = ((n == 0 ? 1 : n) + alignment - 1) / alignment * alignment;
    if (void* p = std::aligned_alloc(alignment, rounded)) return p;
    throw std::bad_alloc();
}

struct Installed {
    Installed() { lodestone::memguard::markHooksInstalled(); }
} installed;
}  // namespace

void* operator new(std::size_t n) { return allocate(n); }
void* operator new[](std::size_t n) { return allocate(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
    try {
        return allocate(n);
    } catch (...) {
        return nullptr;
    }
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
    try {
        return allocate(n);
    } catch (...) {
        return nullptr;
    }
}
void* operator new(std::size_t n, std::align_val_t a) {
    return allocateAligned(n, static_cast<std::size_t>(a));
}
void* operator new[](std::size_t n, std::align_val_t a) {
    return allocateAligned(n, static_cast<std::size_t>(a));
}
void* operator new(std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
    try {
        return allocateAligned(n, static_cast<std::size_t>(a));
    } catch (...) {
        return nullptr;
    }
}
void* operator new[](std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
    try {
        return allocateAligned(n, static_cast<std::size_t>(a));
    } catch (...) {
        return nullptr;
    }
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }

namespace mrpt {
void* aligned_malloc(std::size_t size, std::size_t alignment);
void* aligned_calloc(std::size_t bytes, std::size_t alignment);

void* aligned_malloc(std::size_t size, std::size_t alignment) {
    if (!charge(size)) throw std::bad_alloc();
    if (alignment != 0 && size % alignment != 0) size = (size / alignment + 1) * alignment;
    return std::aligned_alloc(alignment, size);
}

void* aligned_calloc(std::size_t bytes, std::size_t alignment) {
    void* p = aligned_malloc(bytes, alignment);
    if (p) std::memset(p, 0, bytes);
    return p;
}
}  // namespace mrpt
