// WarmStartCache: recall by key, whatever order the rows come in and however the remembered
// order changes (the index by key is rebuilt only when the keys change).

#include "dynamics/warm_start.h"

#include <gtest/gtest.h>

#include <vector>

namespace af {
namespace {

struct Recalled {
    std::vector<LcpRowState> states;
    std::vector<Real> impulses;
    int found = 0;
};

Recalled recall(const WarmStartCache& cache, const std::vector<std::uint64_t>& keys) {
    Recalled r;
    r.states.assign(keys.size(), LcpRowState::Free);
    r.impulses.assign(keys.size(), -1);
    r.found = cache.recall(keys, r.states, r.impulses);
    return r;
}

// The impulse remembered for key k is k / 10, its state AtLower for even keys.
void remember(WarmStartCache& cache, const std::vector<std::uint64_t>& keys) {
    std::vector<LcpRowState> states;
    std::vector<Real> impulses;
    for (const std::uint64_t k : keys) {
        states.push_back(k % 2 == 0 ? LcpRowState::AtLower : LcpRowState::Free);
        impulses.push_back(static_cast<Real>(k) / 10);
    }
    cache.remember(keys, states, impulses);
}

void expectRemembered(const Recalled& r, const std::vector<std::uint64_t>& keys, std::uint64_t unknown) {
    for (std::size_t i = 0; i < keys.size(); ++i) {
        if (keys[i] == unknown) {
            EXPECT_EQ(r.states[i], LcpRowState::Unknown);
            EXPECT_EQ(r.impulses[i], 0);
        } else {
            EXPECT_EQ(r.states[i], keys[i] % 2 == 0 ? LcpRowState::AtLower : LcpRowState::Free) << "key " << keys[i];
            EXPECT_EQ(r.impulses[i], static_cast<Real>(keys[i]) / 10) << "key " << keys[i];
        }
    }
}

TEST(WarmStart, RecallsByKeyInAnyOrderAndStartsUnknownRowsFromNothing) {
    WarmStartCache cache;
    remember(cache, {10, 20, 30, 40});
    const std::vector<std::uint64_t> keys{40, 10, 99, 20, 30};
    const Recalled r = recall(cache, keys);
    EXPECT_EQ(r.found, 4);
    expectRemembered(r, keys, 99);
}

TEST(WarmStart, SameKeysInAnotherOrderAreStillFound) {
    WarmStartCache cache;
    remember(cache, {1, 2, 3, 4, 5});
    remember(cache, {5, 3, 1, 4, 2});
    const std::vector<std::uint64_t> keys{2, 4, 1, 3, 5};
    const Recalled r = recall(cache, keys);
    EXPECT_EQ(r.found, 5);
    expectRemembered(r, keys, 0);
    remember(cache, {5, 3, 1, 4});  // one fewer
    const Recalled fewer = recall(cache, keys);
    EXPECT_EQ(fewer.found, 4);
    expectRemembered(fewer, keys, 2);
}

TEST(WarmStart, CacheBuiltFromOthersFindsEveryonesRows) {
    WarmStartCache a, b, all;
    remember(a, {7, 3});
    remember(b, {8, 4, 6});
    for (int round = 0; round < 3; ++round) {  // the second keeps the index, the third reorders
        all.clear();
        all.add(round < 2 ? a : b);
        all.add(round < 2 ? b : a);
        all.sort();
        const std::vector<std::uint64_t> keys{6, 7, 8, 3, 4, 5};
        const Recalled r = recall(all, keys);
        EXPECT_EQ(r.found, 5);
        expectRemembered(r, keys, 5);
    }
}

}  // namespace
}  // namespace af
