#pragma once
// Disjoint sets over 0..n-1 as a parent array (union-find with path halving): bodies joined into
// islands, figures into groups that rest together, joints into SHAKE's blocks.

#include <cstddef>
#include <vector>

namespace af {

inline int findRoot(std::vector<int>& parent, int i) {
    while (parent[static_cast<std::size_t>(i)] != i) {
        parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
        i = parent[static_cast<std::size_t>(i)];
    }
    return i;
}

inline void joinSets(std::vector<int>& parent, int a, int b) {
    parent[static_cast<std::size_t>(findRoot(parent, a))] = findRoot(parent, b);
}

}  // namespace af
