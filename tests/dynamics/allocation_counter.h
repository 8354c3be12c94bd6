#pragma once
// Counts every heap allocation of the program, so that a test or benchmark can tell that a solve
// made none. The replaced global operator new/delete may be defined once per program: include
// this from exactly one file of it. GCC takes the replaced pair for the library's and warns that
// malloc'ed memory meets delete.

#include <atomic>
#include <cstdlib>
#include <new>

namespace af::test {
inline std::atomic<long> gAllocations{0};
}  // namespace af::test

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
void* operator new(std::size_t size) {
    ++af::test::gAllocations;
    if (void* p = std::malloc(size > 0 ? size : 1)) return p;
    throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
