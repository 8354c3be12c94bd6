#pragma once
// Warm starts keyed by row identity. Every row of a step carries a key naming what wrote it (a
// joint and the row's place in it, or a contact point and the row's place in it); the next step
// starts each row from the state and impulse the row with the same key ended with, whatever rows
// came or went in between (limits engaging, contact points appearing). Rows never seen start
// Unknown with no impulse.
//
// Rows usually come in the same order step after step (a resting figure's), so entries are kept
// in the order they were remembered and a recall first tries the entry after the last one found;
// only rows out of that order are looked up by key. The index by key is built by the first recall
// that needs it, so a cache recalled only in order (or never: an island's velocity cache, which
// the world merges into its own) never builds or checks it.

#include "lcp.h"

#include <cstdint>
#include <span>
#include <vector>

namespace af {

class WarmStartCache {
public:
    void remember(std::span<const std::uint64_t> keys, std::span<const LcpRowState> states,
                  std::span<const Real> impulses);
    // Fills the guesses of `keys`; returns how many rows were found.
    int recall(std::span<const std::uint64_t> keys, std::span<LcpRowState> states, std::span<Real> impulses) const;
    // The impulse each of `keys` ended with, 0 for a key not remembered. Builds no index: for
    // queries between steps (World::contactImpulses), which several threads may make at once.
    void impulsesOf(std::span<const std::uint64_t> keys, std::span<Real> impulses) const;
    // Keeps the index by key, so that one after the same adds as last time has nothing to rebuild.
    void clear() {
        entries_.clear();
        indexChecked_ = false;
    }
    // Builds the cache from others with disjoint keys (the islands of a step): clear, then add each.
    void add(const WarmStartCache& other) {
        entries_.insert(entries_.end(), other.entries_.begin(), other.entries_.end());
        indexChecked_ = false;
    }
    // Builds the index by key now (a recall that needs it would otherwise build it).
    void sort() const;
    // Forgets the entries whose impulse is a NaN or an infinity (a step the world's guard undid).
    void forgetNonFinite();

private:
    struct Entry {
        std::uint64_t key;
        LcpRowState state;
        Real impulse;
    };
    std::vector<Entry> entries_;  // in the order remembered
    // The index, built on demand by const recalls: an island's caches are used by one thread, and
    // the world's is indexed (sort) before its islands recall from it on several.
    mutable std::vector<std::pair<std::uint64_t, std::size_t>> byKey_;  // (key, index into entries_), sorted
    mutable std::vector<std::uint64_t> indexedKeys_;  // the entries' keys byKey_ was built from
    mutable bool indexChecked_ = false;                // byKey_ is known to index entries_
};

}  // namespace af
