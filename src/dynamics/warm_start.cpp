#include "warm_start.h"

#include <algorithm>

namespace af {

void WarmStartCache::remember(std::span<const std::uint64_t> keys, std::span<const LcpRowState> states,
                              std::span<const Real> impulses) {
    entries_.clear();
    for (std::size_t i = 0; i < keys.size(); ++i) entries_.push_back({keys[i], states[i], impulses[i]});
    std::sort(entries_.begin(), entries_.end());
}

void WarmStartCache::sort() { std::sort(entries_.begin(), entries_.end()); }

int WarmStartCache::recall(std::span<const std::uint64_t> keys, std::span<LcpRowState> states,
                           std::span<Real> impulses) const {
    int found = 0;
    for (std::size_t i = 0; i < keys.size(); ++i) {
        const auto at = std::lower_bound(entries_.begin(), entries_.end(), Entry{keys[i], LcpRowState::Unknown, 0});
        if (at != entries_.end() && at->key == keys[i]) {
            states[i] = at->state;
            impulses[i] = at->impulse;
            ++found;
        } else {
            states[i] = LcpRowState::Unknown;
            impulses[i] = 0;
        }
    }
    return found;
}

}  // namespace af
