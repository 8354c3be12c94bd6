#pragma once
// Counts every heap allocation of the program, so that a test or benchmark can tell that a solve
// made none. The replaced global operator new/delete may be defined once per program: include
// this from exactly one file of it. GCC takes the replaced pair for the library's and warns that
// malloc'ed memory meets delete.
//
// Every form that allocates is replaced, the nothrow and array ones too: the standard library
// takes some of those (std::stable_sort's temporary buffer is nothrow new), and under
// AddressSanitizer one left to the sanitizer's allocator would be freed here by free(), which it
// reports as a mismatch.

#include <atomic>
#include <cstdlib>
#include <new>

namespace af::test {
inline std::atomic<long> gAllocations{0};

inline void* countedAllocation(std::size_t size) noexcept {
    ++gAllocations;
    return std::malloc(size > 0 ? size : 1);
}
}  // namespace af::test

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
void* operator new(std::size_t size) {
    if (void* p = af::test::countedAllocation(size)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t size) {
    if (void* p = af::test::countedAllocation(size)) return p;
    throw std::bad_alloc();
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept { return af::test::countedAllocation(size); }
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept { return af::test::countedAllocation(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
