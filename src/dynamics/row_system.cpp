#include "row_system.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace af {

namespace {

// accumulateResponses with the rows' bodies given by bodiesOf(i) (a pair: A, B).
template <class BodiesOf>
void accumulate(std::size_t rows, BodiesOf bodiesOf, std::span<const RowResponse> responses,
                std::span<const Real> lambda, std::vector<Vec3>& linear, std::vector<Vec3>& angular) {
    std::fill(linear.begin(), linear.end(), Vec3::Zero());
    std::fill(angular.begin(), angular.end(), Vec3::Zero());
    for (std::size_t i = 0; i < rows; ++i) {
        if (lambda[i] == 0) continue;
        const auto [a, b] = bodiesOf(i);
        const RowResponse& m = responses[i];
        if (a != kWorldBody) {
            linear[static_cast<std::size_t>(a)] += lambda[i] * m.linearA;
            angular[static_cast<std::size_t>(a)] += lambda[i] * m.angularA;
        }
        if (b != kWorldBody) {
            linear[static_cast<std::size_t>(b)] += lambda[i] * m.linearB;
            angular[static_cast<std::size_t>(b)] += lambda[i] * m.angularB;
        }
    }
}

}  // namespace

void RowSystem::build(const ConstraintRows& rows, std::span<const RigidBody> bodies) {
    buildResponses(rows, bodies);
    buildMatrix(rows);
}

void RowSystem::buildResponses(const ConstraintRows& rows, std::span<const RigidBody> bodies) {
    buildResponses(rows, bodies, inverseInertiasWorld(bodies));
}

void RowSystem::buildResponses(const ConstraintRows& rows, std::span<const RigidBody> bodies,
                               std::span<const Mat3> inertia) {
    n_ = static_cast<int>(rows.size());
    const std::size_t n = rows.size();
    // Grown, never shrunk: the loop below writes the first n of each, and setVelocityRhs or
    // setPositionRhs b's, before anything reads them, so zeroing what a resize adds would be
    // wasted (the row count swings between the velocity solve and the projection passes).
    const auto grow = [n](auto& v) {
        if (v.size() < n) v.resize(n);
    };
    grow(response_);
    grow(b_);
    grow(lo_);
    grow(hi_);
    grow(mu_);
    grow(cfm_);
    grow(findex_);
    grow(rowBodies_);
    x_.resize(n);
    states_.resize(n);

    // Through local pointers: a store through a member vector's data could, for all the compiler
    // knows, change the vectors themselves (the rows' too), which it would then reload for every row (resting
    // bench ragdoll: ~1.5k of buildResponses' 10.8k instructions a step).
    const ConstraintRow* const row = rows.all().data();
    RowResponse* const response = response_.data();
    std::array<int, 2>* const rowBodies = rowBodies_.data();
    Real* const lo = lo_.data();
    Real* const hi = hi_.data();
    int* const findex = findex_.data();
    Real* const mu = mu_.data();
    Real* const cfm = cfm_.data();
    for (std::size_t i = 0; i < n; ++i) {
        const ConstraintRow& r = row[i];
        RowResponse& m = response[i];
        auto side = [&](int body, const Vec3& linear, const Vec3& angular, Vec3& linearOut, Vec3& angularOut) {
            if (body == kWorldBody) {
                linearOut.setZero();
                angularOut.setZero();
                return;
            }
            linearOut = bodies[static_cast<std::size_t>(body)].inverseMass * linear;
            angularOut.noalias() = inertia[static_cast<std::size_t>(body)] * angular;
        };
        side(r.bodyA, r.linearA, r.angularA, m.linearA, m.angularA);
        side(r.bodyB, r.linearB, r.angularB, m.linearB, m.angularB);
        rowBodies[i] = {r.bodyA, r.bodyB};
        lo[i] = r.lo;
        hi[i] = r.hi;
        findex[i] = r.frictionSource;
        mu[i] = r.frictionCoefficient;
        cfm[i] = r.cfm;
    }
}

std::span<const Mat3> RowSystem::inverseInertiasWorld(std::span<const RigidBody> bodies) {
    inverseInertia_.resize(bodies.size());
    for (std::size_t k = 0; k < bodies.size(); ++k) inverseInertia_[k] = bodies[k].inverseInertiaWorld();
    return inverseInertia_;
}

std::span<const Mat3> RowSystem::inverseInertiasWorld(std::span<const RigidBody> bodies, std::span<const Mat3> rotations) {
    inverseInertia_.resize(bodies.size());
    for (std::size_t k = 0; k < bodies.size(); ++k) inverseInertia_[k] = bodies[k].inverseInertiaWorld(rotations[k]);
    return inverseInertia_;
}

void RowSystem::buildMatrix(const ConstraintRows& rows) {
    const std::size_t n = rows.size();
    a_.assign(n * n, 0);
    // A_ij = Σ over the bodies rows i and j share of J_i · M⁻¹ J_jᵀ. Symmetric: fill both halves.
    for (std::size_t i = 0; i < n; ++i) {
        const ConstraintRow& ri = rows[i];
        for (std::size_t j = 0; j <= i; ++j) {
            const ConstraintRow& rj = rows[j];
            const RowResponse& mj = response_[j];
            const Real v = rowCoupling(ri, rj, mj);
            a_[i * n + j] = v;
            a_[j * n + i] = v;
        }
    }
}

void holdFrictionAtZero(ConstraintRows& rows, std::span<const JointRowRange> ranges) {
    for (const JointRowRange& range : ranges)
        for (int q = 0; q < range.frictionRows; ++q) {
            ConstraintRow& row = rows[static_cast<std::size_t>(range.first + range.equalityRows + range.limitRows + q)];
            row.lo = row.hi = 0;
        }
    for (std::size_t i = 0; i < rows.size(); ++i)
        if (rows[i].frictionSource >= 0) {
            rows[i].frictionSource = -1;
            rows[i].lo = rows[i].hi = 0;
        }
}

void RowSystem::setVelocityRhs(const ConstraintRows& rows, std::span<const RigidBody> bodies) {
    for (std::size_t i = 0; i < rows.size(); ++i) b_[i] = rows[i].target - rowVelocity(rows[i], bodies);
}

void RowSystem::setPositionRhs(const ConstraintRows& rows) {
    for (std::size_t i = 0; i < rows.size(); ++i) b_[i] = -rows[i].error;
}

LcpProblem RowSystem::problem() const {
    const std::size_t n = static_cast<std::size_t>(n_);
    const std::span<const int> findex = std::span(findex_).first(n);
    const bool coupled = std::any_of(findex.begin(), findex.end(), [](int f) { return f >= 0; });
    LcpProblem p;
    p.size = n_;
    p.a = a_;
    p.b = std::span(b_).first(n);
    p.lo = std::span(lo_).first(n);
    p.hi = std::span(hi_).first(n);
    if (coupled) {
        p.findex = findex;
        p.mu = std::span(mu_).first(n);
    }
    p.cfm = std::span(cfm_).first(n);
    return p;
}

void accumulateResponses(std::span<const ConstraintRow> rows, std::span<const RowResponse> responses,
                         std::span<const Real> lambda, std::vector<Vec3>& linear, std::vector<Vec3>& angular) {
    accumulate(
        rows.size(), [&](std::size_t i) { return std::array<int, 2>{rows[i].bodyA, rows[i].bodyB}; }, responses, lambda,
        linear, angular);
}

void RowSystem::applyImpulses(const ConstraintRows& rows, std::span<RigidBody> bodies) {
    linearShift_.resize(bodies.size());
    angularShift_.resize(bodies.size());
    accumulateResponses(rows.all(), responses(), x_, linearShift_, angularShift_);
    for (std::size_t k = 0; k < bodies.size(); ++k) {
        bodies[k].linearVelocity += linearShift_[k];
        bodies[k].angularVelocity += angularShift_[k];
    }
}

// Every body moves once, by the sum of its rows' moves, so the order of rows does not matter.
void RowSystem::applyDisplacements(std::span<RigidBody> bodies) {
    linearShift_.resize(bodies.size());
    angularShift_.resize(bodies.size());
    accumulate(
        x_.size(), [&](std::size_t i) { return rowBodies_[i]; }, responses(), x_, linearShift_, angularShift_);
    for (std::size_t k = 0; k < bodies.size(); ++k) displaceBody(bodies[k], linearShift_[k], angularShift_[k]);
}

void displaceBody(RigidBody& body, const Vec3& linear, const Vec3& angular) {
    body.position += linear;
    const Real angle = angular.norm();
    if (angle > 0) {
        body.orientation = Quat(Eigen::AngleAxis<Real>(angle, angular / angle)) * body.orientation;
        body.orientation.normalize();
    }
}

namespace {

// At a bound within `tolerance` relative, or free.
LcpRowState stateWithin(Real x, Real lo, Real hi, Real tolerance) {
    const bool atLower = std::isfinite(lo) && x <= lo + tolerance * std::max(Real(1), std::abs(lo));
    const bool atUpper = std::isfinite(hi) && x >= hi - tolerance * std::max(Real(1), std::abs(hi));
    return atLower ? LcpRowState::AtLower : atUpper ? LcpRowState::AtUpper : LcpRowState::Free;
}

}  // namespace

void statesFromImpulses(const ConstraintRows& rows, std::span<const Real> x, std::span<LcpRowState> states,
                        Real tolerance) {
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const ConstraintRow& r = rows[i];
        if (r.frictionSource < 0) {
            states[i] = stateWithin(x[i], r.lo, r.hi, tolerance);
            continue;
        }
        const Real box = r.frictionCoefficient * std::abs(x[static_cast<std::size_t>(r.frictionSource)]);
        states[i] = stateWithin(x[i], -box, box, tolerance);
    }
}

void statesFromImpulses(const LcpProblem& problem, std::span<const Real> x, std::span<LcpRowState> states,
                        Real tolerance) {
    for (std::size_t i = 0; i < x.size(); ++i) {
        const int source = problem.findex.empty() ? -1 : problem.findex[i];
        if (source < 0) {
            states[i] = stateWithin(x[i], problem.lo[i], problem.hi[i], tolerance);
            continue;
        }
        const Real box = problem.mu[i] * std::abs(x[static_cast<std::size_t>(source)]);
        states[i] = stateWithin(x[i], -box, box, tolerance);
    }
}

}  // namespace af
