#pragma once
// The pair keys of the sparse factorisation (sparse_factor.h): rows are grouped by the pair of
// bodies they join, named by one 64-bit key, (first + 1) << 32 | (second + 1) with first ≤
// second, so that the world and static bodies (kNoBody) are 0 and sort first.

#include <cstdint>
#include <utility>

namespace af::sparse_pairs {

constexpr int kNoBody = -1;

inline std::uint64_t pairKey(int a, int b) {
    if (a > b) std::swap(a, b);
    return (static_cast<std::uint64_t>(a + 1) << 32) | static_cast<std::uint64_t>(b + 1);
}
inline int firstBody(std::uint64_t key) { return static_cast<int>(key >> 32) - 1; }
inline int secondBody(std::uint64_t key) { return static_cast<int>(key & 0xffffffffu) - 1; }

}  // namespace af::sparse_pairs
