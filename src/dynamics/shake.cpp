#include "shake.h"

#include <algorithm>
#include <cmath>

namespace af {

namespace {

enum class RowSide { None, A, B };

// Which side of a joint's rows (joining bodyA and bodyB) is on `body`: none for the world or a
// body the joint does not join.
RowSide sideOf(int bodyA, int bodyB, int body) {
    if (body == kWorldBody) return RowSide::None;
    return bodyA == body ? RowSide::A : bodyB == body ? RowSide::B : RowSide::None;
}

// A row's J₁ on one of its bodies.
struct RowPart {
    Vec3 linear = Vec3::Zero(), angular = Vec3::Zero();
    Real along(const Vec3& moveLinear, const Vec3& moveAngular) const {
        return linear.dot(moveLinear) + angular.dot(moveAngular);
    }
};

RowPart partOf(const ConstraintRow& row, RowSide side) {
    if (side == RowSide::A) return {row.linearA, row.angularA};
    if (side == RowSide::B) return {row.linearB, row.angularB};
    return {};
}

// A length for the body: the radius of gyration, √(trace I / 2m), so a turn can be compared
// with a move of its centre.
Real gyrationRadius(const RigidBody& b) {
    return b.inverseMass > 0 ? std::sqrt(b.inertia.trace() * b.inverseMass / 2) : 0;
}

}  // namespace

void ShakeCorrection::capture(const ConstraintRows& rows, const std::vector<JointRowRange>& ranges,
                              const RowSystem& system, std::span<const char> hold) {
    start_.clear();
    heldLimits_ = false;
    offset_.clear();
    responses_.clear();
    factorised_ = false;
    // The order and the blocks depend only on which bodies the joints join: a figure keeps them
    // from step to step, and they are made again only when those change. How many rows each
    // joint has (its held limits come and go: 35 of 61 settling steps of the bench drop) changes
    // only where the rows sit, which layOut() redoes alone.
    std::size_t count = 0;
    bool same = true, sized = true;
    for (const JointRowRange& range : ranges) {
        if (range.equalityRows == 0) continue;
        const ConstraintRow& row = rows[static_cast<std::size_t>(range.first)];
        if (count == groups_.size()) {
            groups_.emplace_back();
            same = false;
        }
        const int first = static_cast<int>(start_.size());
        for (int r = 0; r < range.equalityRows + range.limitRows; ++r) {
            const std::size_t i = static_cast<std::size_t>(range.first + r);
            const bool limit = r >= range.equalityRows;
            if (limit && !(i < hold.size() && hold[i])) continue;
            const ConstraintRow& row = rows[i];
            start_.push_back({row.bodyA, row.bodyB, limit, row.angularA, limit ? std::min(row.error, Real(0)) : row.error});
            heldLimits_ = heldLimits_ || limit;
            offset_.push_back(r);
            responses_.push_back(system.response(i));
        }
        const int size = static_cast<int>(start_.size()) - first;
        Group& g = groups_[count++];
        same = same && g.bodyA == row.bodyA && g.bodyB == row.bodyB;
        if (!same) {
            g = Group{};
            g.bodyA = row.bodyA;
            g.bodyB = row.bodyB;
        }
        sized = sized && g.first == first && g.size == size;
        g.first = first;
        g.size = size;
    }
    if (same && count == groups_.size() && structured_) {
        if (!sized) layOut();
        return;
    }
    groups_.resize(count);
    findStructure();
}

// K_pq: how row p's error moves per unit impulse along start row q, for every pair of rows the
// factorisation reads (the fill's pairs, which share no body, get 0). Every row of a joint joins
// the joint's two bodies, so which side of p's rows meets each side of q's is found once per
// pair of groups, and p's row is read once for all of q's (bench ragdoll, ~1060 entries: 66k ->
// 51k instructions a fill, against matching bodies entry by entry).
void ShakeCorrection::fillBlock(const Block& block, const ConstraintRows& rows, std::vector<Real>& k) const {
    const std::size_t n = static_cast<std::size_t>(block.size);
    auto fill = [&](const Group& p, const Group& q) {
        const RowSide onA = sideOf(p.bodyA, p.bodyB, q.bodyA), onB = sideOf(p.bodyA, p.bodyB, q.bodyB);
        for (int r = 0; r < p.size; ++r) {
            const ConstraintRow& now = rows[nowRow_[static_cast<std::size_t>(p.first + r)]];
            const RowPart a = partOf(now, onA), b = partOf(now, onB);
            Real* out = &k[static_cast<std::size_t>(p.at.start + r) * n + static_cast<std::size_t>(q.at.start)];
            const RowResponse* m = &responses_[static_cast<std::size_t>(q.first)];
            if (onA != RowSide::None && onB != RowSide::None)
                for (int c = 0; c < q.size; ++c)
                    out[c] = a.along(m[c].linearA, m[c].angularA) + b.along(m[c].linearB, m[c].angularB);
            else if (onA != RowSide::None)
                for (int c = 0; c < q.size; ++c) out[c] = a.along(m[c].linearA, m[c].angularA);
            else if (onB != RowSide::None)
                for (int c = 0; c < q.size; ++c) out[c] = b.along(m[c].linearB, m[c].angularB);
            else
                std::fill(out, out + q.size, Real(0));
        }
    };
    for (int e = 0; e < block.groups; ++e) {
        const Group& g = groups_[static_cast<std::size_t>(eliminated_[static_cast<std::size_t>(block.firstGroup + e)])];
        fill(g, g);
        for (int p = g.laterBegin; p < g.laterEnd; ++p) {
            const Group& h = groups_[static_cast<std::size_t>(later_[static_cast<std::size_t>(p)])];
            fill(g, h);
            fill(h, g);
        }
    }
}

// LU in place, without pivoting: K is J₁ M⁻¹ J₀ᵀ with J₁ close to J₀, so close to symmetric
// positive definite, where no pivoting is needed. False at a zero (or not finite) pivot.
bool ShakeCorrection::factorBlock(const Block& block, std::vector<Real>& k) const {
    const std::size_t n = static_cast<std::size_t>(block.size);
    for (int e = 0; e < block.groups; ++e) {
        const Group& g = groups_[static_cast<std::size_t>(eliminated_[static_cast<std::size_t>(block.firstGroup + e)])];
        for (int t = 0; t < g.at.size; ++t) {
            const std::size_t r = static_cast<std::size_t>(g.at.start + t);
            const Real pivot = k[r * n + r];
            if (!(std::abs(pivot) > 0) || !std::isfinite(pivot)) return false;
            const std::span<const int> later = laterRowsOf(g, t);
            const Real* pivotRow = &k[r * n];
            for (const int i : later) {
                Real* row = &k[static_cast<std::size_t>(i) * n];
                const Real l = row[r] /= pivot;
                if (l == 0) continue;
                // Unrolled (here and in solveBlock): these loops run over a few places each, and
                // their own count and jump were near a third of their instructions.
#pragma GCC unroll 4
                for (const int j : later) row[j] -= l * pivotRow[j];
            }
        }
    }
    return true;
}

// y ← K⁻¹ y with the factors of factorBlock: L (unit lower) forwards, then U backwards.
void ShakeCorrection::solveBlock(const Block& block, const std::vector<Real>& k, Real* y) const {
    const std::size_t n = static_cast<std::size_t>(block.size);
    for (int e = 0; e < block.groups; ++e) {
        const Group& g = groups_[static_cast<std::size_t>(eliminated_[static_cast<std::size_t>(block.firstGroup + e)])];
        for (int t = 0; t < g.at.size; ++t) {
            const std::size_t r = static_cast<std::size_t>(g.at.start + t);
            // Read once: the stores to y[i] would otherwise make y[r] load again (later rows are
            // never r).
            const Real yr = y[r];
            const Real* column = k.data() + r;
#pragma GCC unroll 4
            for (const int i : laterRowsOf(g, t)) y[i] -= column[static_cast<std::size_t>(i) * n] * yr;
        }
    }
    for (int e = block.groups - 1; e >= 0; --e) {
        const Group& g = groups_[static_cast<std::size_t>(eliminated_[static_cast<std::size_t>(block.firstGroup + e)])];
        for (int t = g.at.size - 1; t >= 0; --t) {
            const std::size_t r = static_cast<std::size_t>(g.at.start + t);
            const Real* row = &k[r * n];
            Real sum = y[r];
#pragma GCC unroll 4
            for (const int j : laterRowsOf(g, t)) sum -= row[j] * y[j];
            y[r] = sum / row[r];
        }
    }
}

namespace {

template <class Rows>
Real equalityDrift(const ConstraintRows& start, const std::vector<JointRowRange>& startRanges, const Rows& now,
                   const std::vector<JointRowRange>& ranges) {
    Real worst = 0;
    for (std::size_t k = 0; k < ranges.size(); ++k)
        for (int r = 0; r < ranges[k].equalityRows; ++r) {
            const Real error = now[static_cast<std::size_t>(ranges[k].first + r)].error;
            worst = std::max(worst, std::abs(error - start[static_cast<std::size_t>(startRanges[k].first + r)].error));
        }
    return worst;
}

}  // namespace

Real ShakeCorrection::drift(const ConstraintRows& start, const std::vector<JointRowRange>& startRanges,
                            std::span<const RowError> errors, const std::vector<JointRowRange>& ranges) {
    return equalityDrift(start, startRanges, errors, ranges);
}

Real ShakeCorrection::drift(const ConstraintRows& start, const std::vector<JointRowRange>& startRanges,
                            const ConstraintRows& rows, const std::vector<JointRowRange>& ranges) {
    return equalityDrift(start, startRanges, rows, ranges);
}

// drift_ from the errors now, errorOf(i) for row i of `ranges`; false when a captured limit row
// is not there, or sameLimit(i, captured row) says it turns another way (a pyramid's other face
// could have taken its place).
template <class ErrorOf, class SameLimit>
bool ShakeCorrection::measureDrift(const std::vector<JointRowRange>& ranges, ErrorOf errorOf, SameLimit sameLimit,
                                   Step& step) {
    const std::size_t n = start_.size();
    drift_.resize(n);
    nowRow_.resize(n);
    std::size_t i = 0, group = 0;
    bool found = true;
    for (const JointRowRange& range : ranges) {
        if (range.equalityRows == 0) continue;
        if (group == groups_.size()) {
            step.drift = kInfinity;
            return false;
        }
        const std::size_t end = i + static_cast<std::size_t>(groups_[group++].size);
        for (; i < end; ++i) {
            const int r = offset_[i];
            const bool there = r < range.equalityRows + range.limitRows;
            nowRow_[i] = static_cast<std::size_t>(range.first + (there ? r : 0));
            if (r >= range.equalityRows && !(there && sameLimit(nowRow_[i], i))) found = false;
            drift_[i] = errorOf(nowRow_[i]) - start_[i].error;
            step.drift = std::max(step.drift, std::abs(drift_[i]));
        }
    }
    return found;
}

ShakeCorrection::Step ShakeCorrection::apply(const ConstraintRows& rows, const std::vector<JointRowRange>& ranges,
                                             std::span<RigidBody> bodies, Real dt, Real closed) {
    Step step;
    if (start_.empty()) return step;
    const bool found = measureDrift(
        ranges, [&](std::size_t r) { return rows[r].error; },
        [&](std::size_t r, std::size_t c) { return rows[r].angularA.dot(start_[c].angularA) > 0; }, step);
    if (!found) return {step.drift, kInfinity};
    if (step.drift <= closed) return step;
    // Later steps after a capture reuse the first one's factors (simplified Newton): the bodies
    // have moved since only by a correction the size of the drift, which changes K by as little.
    if (!factorised_) factorise(rows);
    move(bodies, dt, step);
    return step;
}

void ShakeCorrection::factorise(const ConstraintRows& rows) {
    singular_ = false;
    for (std::size_t b = 0; b < blockCount_; ++b) {
        Block& block = blocks_[b];
        block.k.resize(static_cast<std::size_t>(block.size) * static_cast<std::size_t>(block.size));
        fillBlock(block, rows, block.k);
        singular_ = singular_ || !factorBlock(block, block.k);
    }
    factorised_ = true;
}

Real ShakeCorrection::keptKineticEnergy(const ConstraintRows& rows, const std::vector<JointRowRange>& ranges,
                                        std::span<const RigidBody> bodies) {
    Step unused;
    measureDrift(
        ranges, [&](std::size_t r) { return rows[r].error; }, [](std::size_t, std::size_t) { return true; }, unused);
    // The rows' velocities take the place of the drift: λ = −K⁻¹ J v is the projection's impulse.
    for (std::size_t c = 0; c < start_.size(); ++c) drift_[c] = rowVelocity(rows[nowRow_[c]], bodies);
    factorise(rows);
    if (singular_) return kInfinity;
    solveLambda();
    sumResponses(bodies.size());
    Real kept = 0;
    for (std::size_t b = 0; b < bodies.size(); ++b) {
        RigidBody body = bodies[b];
        body.linearVelocity += linear_[b];
        body.angularVelocity += angular_[b];
        kept += body.kineticEnergy();
    }
    return kept;
}

ShakeCorrection::Step ShakeCorrection::applyAgain(std::span<const RowError> errors, const std::vector<JointRowRange>& ranges,
                                                  std::span<RigidBody> bodies, Real dt) {
    Step step;
    if (start_.empty()) return step;
    if (!factorised_) return {kInfinity, kInfinity};
    const bool found = measureDrift(
        ranges, [&](std::size_t r) { return errors[r].error; }, [](std::size_t, std::size_t) { return true; }, step);
    if (!found) return {step.drift, kInfinity};
    if (step.drift > 0) move(bodies, dt, step);
    return step;
}

// λ = −K⁻¹ drift_ with the factors of K.
void ShakeCorrection::solveLambda() {
    const std::size_t n = start_.size();
    lambda_.resize(n);
    for (std::size_t b = 0; b < blockCount_; ++b) {
        const Block& block = blocks_[b];
        y_.resize(static_cast<std::size_t>(block.size));
        const int* captured = order_.data() + block.firstRow;
        for (int p = 0; p < block.size; ++p) y_[static_cast<std::size_t>(p)] = -drift_[static_cast<std::size_t>(captured[p])];
        solveBlock(block, block.k, y_.data());
        for (int p = 0; p < block.size; ++p) lambda_[static_cast<std::size_t>(captured[p])] = y_[static_cast<std::size_t>(p)];
    }
}

// Per body, λ times the rows' responses (linear_, angular_) and the held limits' share of it,
// summed in one pass over the rows in the order accumulateResponses (row_system.h) takes, so
// each sum is the same to the bit.
void ShakeCorrection::sumResponses(std::size_t bodies) {
    const std::size_t n = start_.size();
    for (std::vector<Vec3>* sum : {&linear_, &angular_}) sum->assign(bodies, Vec3::Zero());
    if (heldLimits_)
        for (std::vector<Vec3>* sum : {&limitLinear_, &limitAngular_}) sum->assign(bodies, Vec3::Zero());
    for (std::size_t c = 0; c < n; ++c) {
        const Real l = lambda_[c];
        if (l == 0) continue;
        const StartRow& row = start_[c];
        const RowResponse& m = responses_[c];
        const bool limit = row.limit;
        auto add = [&](int body, const Vec3& linear, const Vec3& angular) {
            if (body == kWorldBody) return;
            const std::size_t b = static_cast<std::size_t>(body);
            linear_[b] += l * linear;
            angular_[b] += l * angular;
            if (!limit) return;
            limitLinear_[b] += l * linear;
            limitAngular_[b] += l * angular;
        };
        add(row.bodyA, m.linearA, m.angularA);
        add(row.bodyB, m.linearB, m.angularB);
    }
}

// λ = −K⁻¹ drift_ with the factors of K; the bodies move by M⁻¹J₀ᵀλ and their velocities
// change by the equality rows' share of it over dt.
void ShakeCorrection::move(std::span<RigidBody> bodies, Real dt, Step& step) {
    if (singular_) {
        // No finite move closes this drift: report one too large to be kept.
        step.move = kInfinity;
        return;
    }
    solveLambda();
    sumResponses(bodies.size());
    // Read into locals: the call to displaceBody (out of line) would otherwise make heldLimits_
    // and step.move load (and the latter store) again for each body.
    const bool held = heldLimits_;
    Real largest = step.move;
    for (std::size_t b = 0; b < bodies.size(); ++b) {
        const Vec3& linear = linear_[b];
        const Vec3& angular = angular_[b];
        RigidBody& body = bodies[b];
        displaceBody(body, linear, angular);
        body.linearVelocity += (held ? linear - limitLinear_[b] : linear) / dt;
        body.angularVelocity += (held ? angular - limitAngular_[b] : angular) / dt;
        largest = std::max(largest, linear.norm() + angular.norm() * gyrationRadius(body));
    }
    step.move = largest;
}

}  // namespace af
