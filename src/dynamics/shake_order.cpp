// The structure of SHAKE's factorisation (shake.h): which joints' rows couple (blocks, the
// bodies they share), the order in which its groups are eliminated, and where each group's rows
// sit. Made again only when the joints join other bodies.

#include "shake.h"

#include "disjoint_sets.h"

#include <algorithm>
#include <numeric>

namespace af {

void ShakeCorrection::findStructure() {
    structured_ = true;
    int bodies = 0;
    for (const Group& g : groups_) bodies = std::max({bodies, g.bodyA + 1, g.bodyB + 1});
    parent_.resize(static_cast<std::size_t>(bodies));
    std::iota(parent_.begin(), parent_.end(), 0);
    for (const Group& g : groups_)
        if (g.bodyA != kWorldBody && g.bodyB != kWorldBody)
            joinSets(parent_, g.bodyA, g.bodyB);
    // Blocks in the order of their first group.
    blockOfRoot_.assign(static_cast<std::size_t>(bodies), -1);
    blockCount_ = 0;
    for (Group& g : groups_) {
        int& block = blockOfRoot_[static_cast<std::size_t>(findRoot(parent_, g.bodyA != kWorldBody ? g.bodyA : g.bodyB))];
        if (block < 0) block = static_cast<int>(blockCount_++);
        g.block = block;
    }
    orderGroups(bodies);

    // Stable by block, so each block's groups keep the elimination order.
    std::stable_sort(eliminated_.begin(), eliminated_.end(), [&](int x, int y) {
        return groups_[static_cast<std::size_t>(x)].block < groups_[static_cast<std::size_t>(y)].block;
    });
    layOut();
}

// Where each group's rows sit in its block, block by block in the elimination order.
void ShakeCorrection::layOut() {
    if (blocks_.size() < blockCount_) blocks_.resize(blockCount_);
    for (std::size_t b = 0; b < blockCount_; ++b) blocks_[b].size = blocks_[b].groups = 0;
    order_.clear();
    for (std::size_t e = 0; e < eliminated_.size(); ++e) {
        Group& g = groups_[static_cast<std::size_t>(eliminated_[e])];
        Block& block = blocks_[static_cast<std::size_t>(g.block)];
        if (block.groups == 0) {
            block.firstGroup = static_cast<int>(e);
            block.firstRow = static_cast<int>(order_.size());
        }
        ++block.groups;
        g.at = {block.size, g.size};
        block.size += g.size;
        for (int r = 0; r < g.size; ++r) order_.push_back(g.first + r);
    }
    laterRows_.clear();
    for (Group& g : groups_) {
        g.rowsBegin = static_cast<int>(laterRows_.size());
        for (int r = 0; r < g.at.size; ++r) laterRows_.push_back(g.at.start + r);
        for (int p = g.laterBegin; p < g.laterEnd; ++p) {
            const Range& h = groups_[static_cast<std::size_t>(later_[static_cast<std::size_t>(p)])].at;
            for (int r = 0; r < h.size; ++r) laterRows_.push_back(h.start + r);
        }
        g.rowsEnd = static_cast<int>(laterRows_.size());
    }
}

// Elimination order over all groups (blocks never share a neighbour): simplicial groups (whose
// neighbours are all coupled to each other) first; when none is left (a loop), the group with
// fewest neighbours, and its neighbours become coupled (fill).
void ShakeCorrection::orderGroups(int bodies) {
    const std::size_t count = groups_.size();
    // Groups at each body, as one list cut by body.
    bodyGroupsBegin_.assign(static_cast<std::size_t>(bodies) + 1, 0);
    for (const Group& g : groups_)
        for (const int b : {g.bodyA, g.bodyB})
            if (b != kWorldBody) ++bodyGroupsBegin_[static_cast<std::size_t>(b) + 1];
    std::partial_sum(bodyGroupsBegin_.begin(), bodyGroupsBegin_.end(), bodyGroupsBegin_.begin());
    bodyGroups_.resize(static_cast<std::size_t>(bodyGroupsBegin_.back()));
    pending_.assign(bodyGroupsBegin_.begin(), bodyGroupsBegin_.end() - 1);
    for (std::size_t i = 0; i < count; ++i)
        for (const int b : {groups_[i].bodyA, groups_[i].bodyB})
            if (b != kWorldBody) bodyGroups_[static_cast<std::size_t>(pending_[static_cast<std::size_t>(b)]++)] = static_cast<int>(i);

    stamp_.assign(count, 0);
    stampValue_ = 0;
    adjacent_.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
        std::vector<int>& adjacent = adjacent_[i];
        adjacent.clear();
        ++stampValue_;
        stamp_[i] = stampValue_;
        for (const int b : {groups_[i].bodyA, groups_[i].bodyB}) {
            if (b == kWorldBody) continue;
            for (int k = bodyGroupsBegin_[static_cast<std::size_t>(b)]; k < bodyGroupsBegin_[static_cast<std::size_t>(b) + 1]; ++k) {
                const int h = bodyGroups_[static_cast<std::size_t>(k)];
                if (stamp_[static_cast<std::size_t>(h)] != stampValue_) {
                    stamp_[static_cast<std::size_t>(h)] = stampValue_;
                    adjacent.push_back(h);
                }
            }
        }
    }

    done_.assign(count, 0);
    eliminated_.clear();
    later_.clear();
    pending_.resize(count);
    for (std::size_t i = 0; i < count; ++i) pending_[i] = static_cast<int>(count - 1 - i);
    while (eliminated_.size() < count) {
        if (pending_.empty()) {
            int best = -1;
            std::size_t fewest = 0;
            for (std::size_t i = 0; i < count; ++i) {
                if (done_[i]) continue;
                const std::size_t degree = static_cast<std::size_t>(std::count_if(
                    adjacent_[i].begin(), adjacent_[i].end(), [&](int h) { return !done_[static_cast<std::size_t>(h)]; }));
                if (best < 0 || degree < fewest) {
                    best = static_cast<int>(i);
                    fewest = degree;
                }
            }
            eliminate(best);
            continue;
        }
        const int g = pending_.back();
        pending_.pop_back();
        if (!done_[static_cast<std::size_t>(g)] && simplicial(g)) eliminate(g);
    }
}

bool ShakeCorrection::simplicial(int group) {
    const std::vector<int>& around = adjacent_[static_cast<std::size_t>(group)];
    for (const int a : around) {
        if (done_[static_cast<std::size_t>(a)]) continue;
        ++stampValue_;
        stamp_[static_cast<std::size_t>(a)] = stampValue_;
        for (const int h : adjacent_[static_cast<std::size_t>(a)]) stamp_[static_cast<std::size_t>(h)] = stampValue_;
        for (const int b : around)
            if (!done_[static_cast<std::size_t>(b)] && stamp_[static_cast<std::size_t>(b)] != stampValue_) return false;
    }
    return true;
}

void ShakeCorrection::eliminate(int group) {
    const std::size_t g = static_cast<std::size_t>(group);
    done_[g] = 1;
    eliminated_.push_back(group);
    Group& eliminated = groups_[g];
    eliminated.laterBegin = static_cast<int>(later_.size());
    for (const int a : adjacent_[g])
        if (!done_[static_cast<std::size_t>(a)]) later_.push_back(a);
    eliminated.laterEnd = static_cast<int>(later_.size());
    // Couple the remaining neighbours to each other (no-ops for a simplicial group).
    for (int p = eliminated.laterBegin; p < eliminated.laterEnd; ++p) {
        const int a = later_[static_cast<std::size_t>(p)];
        std::vector<int>& around = adjacent_[static_cast<std::size_t>(a)];
        for (int q = eliminated.laterBegin; q < eliminated.laterEnd; ++q) {
            const int b = later_[static_cast<std::size_t>(q)];
            if (b != a && std::find(around.begin(), around.end(), b) == around.end()) around.push_back(b);
        }
        pending_.push_back(a);
    }
}

}  // namespace af
