#include "shake.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace af {

namespace {

// J₁_i restricted to one body, applied to that body's move.
Real along(const ConstraintRow& row, int body, const Vec3& linear, const Vec3& angular) {
    if (body == kWorldBody) return 0;
    Real v = 0;
    if (row.bodyA == body) v += row.linearA.dot(linear) + row.angularA.dot(angular);
    if (row.bodyB == body) v += row.linearB.dot(linear) + row.angularB.dot(angular);
    return v;
}

// A length for the body: the radius of gyration, √(trace I / 2m), so a turn can be compared
// with a move of its centre.
Real gyrationRadius(const RigidBody& b) {
    return b.inverseMass > 0 ? std::sqrt(b.inertia.trace() * b.inverseMass / 2) : 0;
}

}  // namespace

void ShakeCorrection::capture(const ConstraintRows& rows, const std::vector<JointRowRange>& ranges,
                              const RowSystem& system) {
    start_.clear();
    responses_.clear();
    factorised_ = false;
    for (const JointRowRange& range : ranges)
        for (int r = 0; r < range.equalityRows; ++r) {
            const std::size_t i = static_cast<std::size_t>(range.first + r);
            start_.push_back(rows[i]);
            responses_.push_back(system.response(i));
        }
    findBlocks();
}

namespace {

int findRoot(std::vector<int>& parent, int i) {
    while (parent[static_cast<std::size_t>(i)] != i) {
        parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
        i = parent[static_cast<std::size_t>(i)];
    }
    return i;
}

}  // namespace

void ShakeCorrection::findBlocks() {
    int bodies = 0;
    for (const ConstraintRow& r : start_) bodies = std::max({bodies, r.bodyA + 1, r.bodyB + 1});
    parent_.resize(static_cast<std::size_t>(bodies));
    std::iota(parent_.begin(), parent_.end(), 0);
    for (const ConstraintRow& r : start_)
        if (r.bodyA != kWorldBody && r.bodyB != kWorldBody)
            parent_[static_cast<std::size_t>(findRoot(parent_, r.bodyA))] = findRoot(parent_, r.bodyB);
    // Blocks in the order of their first row; rows keep their order within a block.
    blockOfRoot_.assign(static_cast<std::size_t>(bodies), -1);
    blockOfRow_.resize(start_.size());
    blockCount_ = 0;
    for (std::size_t i = 0; i < start_.size(); ++i) {
        const ConstraintRow& r = start_[i];
        const int body = r.bodyA != kWorldBody ? r.bodyA : r.bodyB;
        int& block = blockOfRoot_[static_cast<std::size_t>(findRoot(parent_, body))];
        if (block < 0) block = static_cast<int>(blockCount_++);
        blockOfRow_[i] = block;
    }
    if (blocks_.size() < blockCount_) blocks_.resize(blockCount_);
    for (std::size_t b = 0; b < blockCount_; ++b) blocks_[b].size = 0;
    for (const int b : blockOfRow_) ++blocks_[static_cast<std::size_t>(b)].size;
    int first = 0;
    for (std::size_t b = 0; b < blockCount_; ++b) {
        blocks_[b].first = first;
        first += blocks_[b].size;
        blocks_[b].size = 0;
    }
    order_.resize(start_.size());
    for (std::size_t i = 0; i < start_.size(); ++i) {
        Block& block = blocks_[static_cast<std::size_t>(blockOfRow_[i])];
        order_[static_cast<std::size_t>(block.first + block.size++)] = static_cast<int>(i);
    }
}

ShakeCorrection::Step ShakeCorrection::apply(const ConstraintRows& rows, const std::vector<JointRowRange>& ranges,
                                             std::span<RigidBody> bodies, Real dt, Real closed) {
    Step step;
    const Eigen::Index n = static_cast<Eigen::Index>(start_.size());
    if (n == 0) return step;
    drift_.resize(n);
    lambda_.resize(n);
    nowRow_.resize(start_.size());
    Eigen::Index i = 0;
    for (const JointRowRange& range : ranges)
        for (int r = 0; r < range.equalityRows; ++r, ++i) {
            nowRow_[static_cast<std::size_t>(i)] = static_cast<std::size_t>(range.first + r);
            drift_[i] = rows[nowRow_[static_cast<std::size_t>(i)]].error - start_[static_cast<std::size_t>(i)].error;
            step.drift = std::max(step.drift, std::abs(drift_[i]));
        }
    if (step.drift <= closed) return step;
    // Later steps after a capture reuse the first one's matrices (simplified Newton): the bodies
    // have moved since only by a correction the size of the drift, which changes K by as little.
    for (std::size_t b = 0; b < blockCount_; ++b) {
        Block& block = blocks_[b];
        const int* rowsOfBlock = order_.data() + block.first;
        if (!factorised_) {
            block.k.resize(block.size, block.size);
            for (int p = 0; p < block.size; ++p) {
                // K_pq: how row p's error moves per unit impulse along start row q.
                const ConstraintRow& now = rows[nowRow_[static_cast<std::size_t>(rowsOfBlock[p])]];
                for (int q = 0; q < block.size; ++q) {
                    const ConstraintRow& s = start_[static_cast<std::size_t>(rowsOfBlock[q])];
                    const RowResponse& m = responses_[static_cast<std::size_t>(rowsOfBlock[q])];
                    block.k(p, q) = along(now, s.bodyA, m.linearA, m.angularA) + along(now, s.bodyB, m.linearB, m.angularB);
                }
            }
            block.lu.compute(block.k);
        }
        block.rhs.resize(block.size);
        for (int p = 0; p < block.size; ++p) block.rhs[p] = -drift_[rowsOfBlock[p]];
        block.rhs = block.lu.solve(block.rhs);
        for (int p = 0; p < block.size; ++p) lambda_[rowsOfBlock[p]] = block.rhs[p];
    }
    factorised_ = true;

    linear_.resize(bodies.size());
    angular_.resize(bodies.size());
    accumulateResponses(start_, responses_, std::span<const Real>(lambda_.data(), static_cast<std::size_t>(n)), linear_,
                        angular_);
    for (std::size_t b = 0; b < bodies.size(); ++b) {
        displaceBody(bodies[b], linear_[b], angular_[b]);
        bodies[b].linearVelocity += linear_[b] / dt;
        bodies[b].angularVelocity += angular_[b] / dt;
        step.move = std::max(step.move, linear_[b].norm() + angular_[b].norm() * gyrationRadius(bodies[b]));
    }
    return step;
}

}  // namespace af
