#include "warm_start.h"

#include <algorithm>
#include <cmath>

namespace af {

void WarmStartCache::remember(std::span<const std::uint64_t> keys, std::span<const LcpRowState> states,
                              std::span<const Real> impulses) {
    entries_.resize(keys.size());
    for (std::size_t i = 0; i < keys.size(); ++i) entries_[i] = {keys[i], states[i], impulses[i]};
    indexChecked_ = false;
}

// The same keys in the same order as when the index was built (a resting figure): it still holds.
void WarmStartCache::sort() const {
    if (indexChecked_) return;
    indexChecked_ = true;
    const bool sameKeys = std::equal(entries_.begin(), entries_.end(), indexedKeys_.begin(), indexedKeys_.end(),
                                     [](const Entry& e, std::uint64_t key) { return e.key == key; });
    if (sameKeys) return;
    indexedKeys_.resize(entries_.size());
    for (std::size_t i = 0; i < entries_.size(); ++i) indexedKeys_[i] = entries_[i].key;
    byKey_.resize(entries_.size());
    for (std::size_t i = 0; i < entries_.size(); ++i) byKey_[i] = {entries_[i].key, i};
    std::sort(byKey_.begin(), byKey_.end());
}

// Read through locals: the stores to states (one byte each) may alias anything, and the loop
// would load entries_'s bounds again after each.
int WarmStartCache::recall(std::span<const std::uint64_t> keys, std::span<LcpRowState> states,
                           std::span<Real> impulses) const {
    const Entry* const entries = entries_.data();
    const std::size_t count = entries_.size();
    const std::uint64_t* const key = keys.data();
    LcpRowState* const state = states.data();
    Real* const impulse = impulses.data();
    int found = 0;
    std::size_t next = 0;  // the entry after the last one found
    for (std::size_t i = 0; i < keys.size(); ++i) {
        std::size_t at = next;
        if (at >= count || entries[at].key != key[i]) {
            sort();
            const auto k = std::lower_bound(byKey_.begin(), byKey_.end(), std::make_pair(key[i], std::size_t(0)));
            if (k == byKey_.end() || k->first != key[i]) {
                state[i] = LcpRowState::Unknown;
                impulse[i] = 0;
                continue;
            }
            at = k->second;  // the index holds entries_'s keys (sort), so entries[at] has key[i]
        }
        state[i] = entries[at].state;
        impulse[i] = entries[at].impulse;
        next = at + 1;
        ++found;
    }
    return found;
}

// The asked keys sorted, and every entry looked for among them: no state of the cache is touched.
void WarmStartCache::impulsesOf(std::span<const std::uint64_t> keys, std::span<Real> impulses) const {
    std::vector<std::pair<std::uint64_t, std::size_t>> asked(keys.size());
    for (std::size_t i = 0; i < keys.size(); ++i) asked[i] = {keys[i], i};
    std::sort(asked.begin(), asked.end());
    std::fill(impulses.begin(), impulses.end(), Real(0));
    for (const Entry& e : entries_)
        for (auto k = std::lower_bound(asked.begin(), asked.end(), std::make_pair(e.key, std::size_t(0)));
             k != asked.end() && k->first == e.key; ++k)
            impulses[k->second] = e.impulse;
}

void WarmStartCache::forgetNonFinite() {
    std::erase_if(entries_, [](const Entry& e) { return !std::isfinite(e.impulse); });
    indexChecked_ = false;
}

}  // namespace af
