// The structure half of the sparse factorisation (sparse_factor.h): rows grouped by the pair of
// bodies they join, the groups' graph, and the minimum-fill elimination order; the numbers are
// factorised and solved in sparse_factor.cpp.

#include "sparse_factor.h"
#include "sparse_pairs.h"

#include <algorithm>

namespace af {

using namespace sparse_pairs;

namespace {

bool shareBody(std::uint64_t g, std::uint64_t h) {
    const int a = firstBody(g), b = secondBody(g), c = firstBody(h), d = secondBody(h);
    return (a != kNoBody && (a == c || a == d)) || (b != kNoBody && (b == c || b == d));
}

}  // namespace

bool SparseRowFactor::analyse(std::span<const ConstraintRow> rows, std::span<const RigidBody> bodies) {
    const int bodyCount = static_cast<int>(bodies.size());
    auto dynamic = [&](int b) { return b != kWorldBody && bodies[static_cast<std::size_t>(b)].inverseMass > 0 ? b : kNoBody; };
    if (sameBodies(rows, bodies)) {
        structureKept_ = true;
        return true;
    }
    // The same body pairs in the same order as last time (a resting figure): nothing to redo.
    bool same = analysed_ && rowKey_.size() == rows.size() && bodyStart_.size() == bodies.size() + 1;
    std::vector<std::uint64_t>& keys = scratchKeys_;
    keys.resize(rows.size());
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const ConstraintRow& r = rows[i];
        const bool inRange = r.bodyA >= kWorldBody && r.bodyA < bodyCount && r.bodyB >= kWorldBody && r.bodyB < bodyCount;
        if (!inRange || (r.bodyA == r.bodyB && r.bodyA != kWorldBody)) {
            groupKeys_.clear();
            analysed_ = false;
            structureKept_ = false;
            return false;
        }
        keys[i] = pairKey(dynamic(r.bodyA), dynamic(r.bodyB));
        same = same && keys[i] == rowKey_[i];
    }
    structureKept_ = same;
    rememberBodies(rows, bodies);
    if (same) return true;
    analysed_ = true;
    rowKey_.assign(keys.begin(), keys.end());
    std::vector<std::uint64_t>& sorted = scratchKeys_;
    sorted.assign(rowKey_.begin(), rowKey_.end());
    std::sort(sorted.begin(), sorted.end());
    sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
    if (sorted != sortedKeys_ || graph_.size() != sorted.size() * words_ || sorted.empty()) {
        sortedKeys_ = sorted;
        connect();
    }
    pairOfRow_.resize(rows.size());
    for (std::size_t i = 0; i < rows.size(); ++i)
        pairOfRow_[i] = static_cast<int>(std::lower_bound(sortedKeys_.begin(), sortedKeys_.end(), rowKey_[i]) - sortedKeys_.begin());
    if (!orderedFor_.empty()) arrange();

    bodyStart_.assign(bodies.size() + 1, 0);
    for (std::size_t i = 0; i < rows.size(); ++i)
        for (int b : {firstBody(rowKey_[i]), secondBody(rowKey_[i])})
            if (b != kNoBody) ++bodyStart_[static_cast<std::size_t>(b) + 1];
    for (std::size_t b = 0; b < bodies.size(); ++b) bodyStart_[b + 1] += bodyStart_[b];
    bodyRows_.resize(static_cast<std::size_t>(bodyStart_.back()));
    fill_.assign(bodyStart_.begin(), bodyStart_.end() - 1);
    for (std::size_t i = 0; i < rows.size(); ++i)
        for (int b : {firstBody(rowKey_[i]), secondBody(rowKey_[i])})
            if (b != kNoBody) bodyRows_[static_cast<std::size_t>(fill_[static_cast<std::size_t>(b)]++)] = static_cast<int>(i);
    return true;
}

// Whether the rows join the bodies of the last analyse() and the same bodies are dynamic: then
// every row's pair is the one it had. Comparing the bodies is cheaper than making the pairs'
// keys to compare (a resting bench ragdoll's 107 rows: 3.8k fewer of its 196k instructions a step).
bool SparseRowFactor::sameBodies(std::span<const ConstraintRow> rows, std::span<const RigidBody> bodies) const {
    if (!analysed_ || rowBodies_.size() != 2 * rows.size() || dynamicBodies_.size() != bodies.size()) return false;
    for (std::size_t b = 0; b < bodies.size(); ++b)
        if ((bodies[b].inverseMass > 0) != (dynamicBodies_[b] != 0)) return false;
    for (std::size_t i = 0; i < rows.size(); ++i)
        if (rows[i].bodyA != rowBodies_[2 * i] || rows[i].bodyB != rowBodies_[2 * i + 1]) return false;
    return true;
}

void SparseRowFactor::rememberBodies(std::span<const ConstraintRow> rows, std::span<const RigidBody> bodies) {
    rowBodies_.resize(2 * rows.size());
    for (std::size_t i = 0; i < rows.size(); ++i) {
        rowBodies_[2 * i] = rows[i].bodyA;
        rowBodies_[2 * i + 1] = rows[i].bodyB;
    }
    dynamicBodies_.resize(bodies.size());
    for (std::size_t b = 0; b < bodies.size(); ++b) dynamicBodies_[b] = bodies[b].inverseMass > 0 ? 1 : 0;
}

// The rows of each group, in the elimination order of order().
void SparseRowFactor::arrange() {
    const std::size_t groups = groupKeys_.size();
    groupOfRow_.resize(pairOfRow_.size());
    rowStart_.assign(groups + 1, 0);
    for (std::size_t i = 0; i < pairOfRow_.size(); ++i) {
        groupOfRow_[i] = positionOf_[static_cast<std::size_t>(pairOfRow_[i])];
        ++rowStart_[static_cast<std::size_t>(groupOfRow_[i]) + 1];
    }
    for (std::size_t g = 0; g < groups; ++g) rowStart_[g + 1] += rowStart_[g];
    groupRows_.resize(pairOfRow_.size());
    fill_.assign(rowStart_.begin(), rowStart_.end() - 1);
    for (std::size_t i = 0; i < pairOfRow_.size(); ++i)
        groupRows_[static_cast<std::size_t>(fill_[static_cast<std::size_t>(groupOfRow_[i])]++)] = static_cast<int>(i);
}

// The graph of the groups: a bit matrix of the pairs sharing a body.
void SparseRowFactor::connect() {
    const std::size_t groups = sortedKeys_.size();
    words_ = (groups + 63) / 64;
    graph_.assign(groups * words_, 0);
    for (std::size_t g = 0; g < groups; ++g)
        for (std::size_t h = g + 1; h < groups; ++h)
            if (shareBody(sortedKeys_[g], sortedKeys_[h])) {
                graph_[g * words_ + h / 64] |= std::uint64_t(1) << (h % 64);
                graph_[h * words_ + g / 64] |= std::uint64_t(1) << (g % 64);
            }
    orderedFor_.clear();
}

// Minimum fill over the groups with free rows (`active`, by pair). A group without any has no
// variables and couples nothing, so it takes no part and goes last with an empty front; leaving
// it in would close loops that are not there (a resting ragdoll's arm lying on its thigh without
// pushing). Always eliminate the group whose neighbours are closest to a clique (none missing
// for a leaf of a tree, so trees get no fill), then the one with fewest neighbours, then the
// first. The neighbours left when a group is eliminated are its front, made a clique (the fill).
// On bit sets, cheap enough to redo whenever the active groups change. Each group's count of
// missing pairs is kept between steps: an elimination changes it only for the front (its
// neighbours and their links change) and the groups next to the front (links among their
// neighbours appear); recounting every group at every step cost O(groups²) (grid4's islands of
// several figures: 3% of the run in this loop).
void SparseRowFactor::order(const std::vector<std::uint8_t>& active) {
    const std::size_t groups = sortedKeys_.size(), words = words_;
    remaining_.assign(words, 0);
    for (std::size_t g = 0; g < groups; ++g)
        if (active[g]) remaining_[g / 64] |= std::uint64_t(1) << (g % 64);
    adjacency_.resize(graph_.size());
    for (std::size_t g = 0; g < groups; ++g)
        for (std::size_t w = 0; w < words; ++w) adjacency_[g * words + w] = graph_[g * words + w] & remaining_[w];
    auto row = [&](std::size_t g) { return adjacency_.data() + g * words; };
    // Pairs of g's remaining neighbours that are not neighbours of each other.
    auto missing = [&](std::size_t g, std::size_t& degree) {
        const std::uint64_t* n = row(g);
        std::size_t links = 0;
        degree = 0;
        for (std::size_t w = 0; w < words; ++w)
            for (std::uint64_t bits = n[w] & remaining_[w]; bits != 0; bits &= bits - 1) {
                ++degree;
                const std::uint64_t* m = row(w * 64 + static_cast<std::size_t>(__builtin_ctzll(bits)));
                // Bit by bit: a word holds a few links, and without -mpopcnt the builtin is a
                // call into libgcc (single 600 steps 0.7M instructions, grid4 200 steps 20M).
                for (std::size_t v = 0; v < words; ++v)
                    for (std::uint64_t both = m[v] & n[v] & remaining_[v]; both != 0; both &= both - 1) ++links;
            }
        return (degree * (degree - 1) - links) / 2;
    };

    missingOf_.resize(groups);
    degreeOf_.resize(groups);
    for (std::size_t w = 0; w < words; ++w)
        for (std::uint64_t bits = remaining_[w]; bits != 0; bits &= bits - 1) {
            const std::size_t g = w * 64 + static_cast<std::size_t>(__builtin_ctzll(bits));
            missingOf_[g] = missing(g, degreeOf_[g]);
        }
    positionOf_.assign(groups, -1);
    groupKeys_.resize(groups);
    frontStart_.assign(groups + 1, 0);
    front_.clear();
    recount_.resize(words);
    std::size_t step = 0;
    for (;; ++step) {
        std::size_t best = groups;
        for (std::size_t w = 0; w < words; ++w)
            for (std::uint64_t bits = remaining_[w]; bits != 0; bits &= bits - 1) {
                const std::size_t g = w * 64 + static_cast<std::size_t>(__builtin_ctzll(bits));
                if (best == groups || missingOf_[g] < missingOf_[best] ||
                    (missingOf_[g] == missingOf_[best] && degreeOf_[g] < degreeOf_[best]))
                    best = g;
            }
        if (best == groups) break;
        remaining_[best / 64] &= ~(std::uint64_t(1) << (best % 64));
        const std::size_t first = front_.size();
        for (std::size_t w = 0; w < words; ++w)
            for (std::uint64_t bits = row(best)[w] & remaining_[w]; bits != 0; bits &= bits - 1)
                front_.push_back(static_cast<int>(w * 64 + static_cast<std::size_t>(__builtin_ctzll(bits))));
        for (std::size_t u = first; u < front_.size(); ++u) {
            std::uint64_t* r = row(static_cast<std::size_t>(front_[u]));
            for (std::size_t v = first; v < front_.size(); ++v)
                if (u != v) r[static_cast<std::size_t>(front_[v]) / 64] |= std::uint64_t(1) << (front_[v] % 64);
        }
        // The front and its neighbours are the groups whose count may have changed.
        std::fill(recount_.begin(), recount_.end(), 0);
        for (std::size_t u = first; u < front_.size(); ++u) {
            const std::uint64_t* r = row(static_cast<std::size_t>(front_[u]));
            recount_[static_cast<std::size_t>(front_[u]) / 64] |= std::uint64_t(1) << (front_[u] % 64);
            for (std::size_t w = 0; w < words; ++w) recount_[w] |= r[w];
        }
        for (std::size_t w = 0; w < words; ++w)
            for (std::uint64_t bits = recount_[w] & remaining_[w]; bits != 0; bits &= bits - 1) {
                const std::size_t g = w * 64 + static_cast<std::size_t>(__builtin_ctzll(bits));
                missingOf_[g] = missing(g, degreeOf_[g]);
            }
        positionOf_[best] = static_cast<int>(step);
        groupKeys_[step] = sortedKeys_[best];
        frontStart_[step + 1] = static_cast<int>(front_.size());
    }
    for (std::size_t g = 0; g < groups; ++g)
        if (positionOf_[g] < 0) {
            positionOf_[g] = static_cast<int>(step);
            groupKeys_[step] = sortedKeys_[g];
            frontStart_[++step] = static_cast<int>(front_.size());
        }
    for (int& f : front_) f = positionOf_[static_cast<std::size_t>(f)];
    for (std::size_t g = 0; g < groups; ++g)
        std::sort(front_.begin() + frontStart_[g], front_.begin() + frontStart_[g + 1]);
    orderedFor_ = active;
}

}  // namespace af
