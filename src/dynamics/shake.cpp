#include "shake.h"

#include <algorithm>
#include <cmath>

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
}

ShakeCorrection::Step ShakeCorrection::apply(const ConstraintRows& rows, const std::vector<JointRowRange>& ranges,
                                             std::span<RigidBody> bodies, Real dt) {
    Step step;
    const Eigen::Index n = static_cast<Eigen::Index>(start_.size());
    if (n == 0) return step;
    drift_.resize(n);
    if (!factorised_) k_.setZero(n, n);
    Eigen::Index i = 0;
    for (const JointRowRange& range : ranges)
        for (int r = 0; r < range.equalityRows; ++r, ++i) {
            const ConstraintRow& now = rows[static_cast<std::size_t>(range.first + r)];
            drift_[i] = now.error - start_[static_cast<std::size_t>(i)].error;
            step.drift = std::max(step.drift, std::abs(drift_[i]));
            if (factorised_) continue;
            // K_ij: how row i's error moves per unit impulse along start row j.
            for (Eigen::Index j = 0; j < n; ++j) {
                const ConstraintRow& s = start_[static_cast<std::size_t>(j)];
                const RowResponse& m = responses_[static_cast<std::size_t>(j)];
                k_(i, j) = along(now, s.bodyA, m.linearA, m.angularA) + along(now, s.bodyB, m.linearB, m.angularB);
            }
        }
    // Later steps after a capture reuse the first one's matrix (simplified Newton): the bodies
    // have moved since only by a correction the size of the drift, which changes K by as little.
    if (!factorised_) {
        lu_.compute(k_);
        factorised_ = true;
    }
    lambda_ = lu_.solve(-drift_);

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
