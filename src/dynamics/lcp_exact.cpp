// Exact solver, the passes: solve the current pattern exactly, check it, and pivot whatever the
// check released, until a pattern holds.
//
// A cold start begins with the unbounded rows clamped and everything else unprocessed
// (uncoupled rows before coupled ones, so friction meets solved normals); a warm start begins
// with the caller's guess factorised. Each pass then
//   1. solves the pattern with friction rows tied to their normals and checks every processed
//      row against the bounds of the result (lcp_exact_pattern.cpp); done when nothing is
//      released and nothing is left to pivot;
//   2. repeats that solve-and-check on the smaller processed set until it holds (each round only
//      shrinks the set, so this ends);
//   3. drives the unprocessed rows by Dantzig pivoting (lcp_exact_pivot.cpp), in reverse order
//      on even passes: a pattern that failed to settle one way is approached from the other
//      side, which breaks the rare cycles of coupled problems.
// Without coupling, pass 2 merely confirms pass 1 (a warm start that holds needs one pass and
// no pivots). A coupled problem that does not settle within maxCouplingPasses is reported as
// NotConverged with the unsettled rows listed; the coupled problem can lack a solution when
// friction is strong, and it need not be unique.
//
// A coupled problem whose guess does not hold in the first pass tries the frozen-box phase
// (frictionBoxPasses) before the coupled passes start over: friction boxes frozen at
// mu·|x_normal| of where that first pass got to (its repaired pattern, less the rows its check
// released, and its impulses), then of each answer, each pass a plain boxed LCP warm-started from
// the last pattern. The first pass starts from the caller's guess and has repaired what single
// pivots could; a guess a step old is usually further off. Plain Dantzig on a convex problem
// never stalls, and when the boxes stop moving the answer is complementary with the coupled
// bounds as well. Boxes that cycle are damped (see solveWithFrozenBoxes). The boxes converge
// only linearly, so each pass that keeps the pattern it started from hands that pattern to a
// short coupled try (usually one pass, no pivots); when the passes run out, the coupled passes
// take over from the last pattern. A warm-started solve that still does not settle starts once
// more from cold, for kColdStartPasses passes.

#include "dynamics/lcp_internal.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace af {

namespace {

// Block-pivoting rounds tried before rows are released to Dantzig pivoting.
constexpr int kMaxFlipRounds = 8;

// The damping of the frozen boxes (see solveWithFrozenBoxes): the least weight of the new
// normals' boxes in a blend with the last boxes. Measured on the hard solves (60 pivots or more)
// of af-sim's humanoid drops (seeds 0-6) and the failing ones of the tree runs, 32 passes: a
// floor of 0.125 left 3 of 379 unsolved, 0.35 one, 0.25 none; starting the weight at 1
// (undamped until the change first grows) cost fewer pivots than starting at 0.5. On 468 such
// solves: 0 unsolved and 90k pivots, where the undamped passes (8, stopping when they cycled)
// left 38 unsolved after 175k.
constexpr Real kMinBoxBlend = 0.25;
// Coupled passes of a try from a frozen pass's pattern: the first repairs the pattern by single
// flips, the second may pivot what that released (one pass alone left one of the 379 unsolved).
// A pattern whose try failed is not tried again until a pass changes it (a landing kept one
// pattern for 20 passes and tried it each time: 139 pivots and a factorisation per try).
constexpr int kCoupledTryPasses = 2;
// Coupled passes of the cold start after a warm-started solve failed. af-sim --seed 34's failed
// dense solve: from the guess (a step old, 58 of 183 rows wrong) the passes released a friction
// row, then it and a joint friction row, in turn for 16 passes, and the frozen boxes drifted off
// the one pattern they kept; cold, 24 pivots in 2 passes (in that step the sparse path's core,
// 47 rows, now settles cold in 19 pivots first). The cold starts that did not settle in 2 passes
// did not in 16 either (that drop's later landings: 965, 1674 and 1702 pivots for nothing; with
// 2 passes 134, 281 and 278).
constexpr int kColdStartPasses = 2;

// The coupled passes from the last frozen pass's pattern (s.boxStates), at most
// kCoupledTryPasses of them. On success x, ioStates and result hold the answer; otherwise only
// the pivots are added to result and x is left as it was.
bool tryCoupled(LcpExactSolver::Impl& s, const LcpProblem& problem, std::span<Real> x,
                std::span<LcpRowState> ioStates, LcpResult& result) {
    s.load(problem, s.boxStates);
    LcpStatus status = LcpStatus::Solved;
    int passes = 0;
    const int maxPasses = std::exchange(s.settings.maxCouplingPasses, kCoupledTryPasses);
    s.settle(false, status, passes);
    s.settings.maxCouplingPasses = maxPasses;
    if (status != LcpStatus::Solved) {
        result.pivots += s.pivots;
        return false;
    }
    const int earlier = result.pivots;
    s.finish(problem, x, ioStates, result, status);
    result.pivots += earlier;
    result.couplingPasses = passes;
    return result.status == LcpStatus::Solved;
}

}  // namespace

LcpExactSolver::LcpExactSolver(const LcpExactSettings& settings) : impl_(std::make_unique<Impl>()) {
    impl_->settings = settings;
}

LcpExactSolver::~LcpExactSolver() = default;
LcpExactSolver::LcpExactSolver(LcpExactSolver&&) noexcept = default;
LcpExactSolver& LcpExactSolver::operator=(LcpExactSolver&&) noexcept = default;

void LcpExactSolver::reserve(int n) { impl_->reserve(n); }

const LcpExactSettings& LcpExactSolver::settings() const { return impl_->settings; }

void LcpExactSolver::setSettings(const LcpExactSettings& settings) { impl_->settings = settings; }

LcpResult LcpExactSolver::solve(const LcpProblem& problem, std::span<Real> outX,
                                std::span<LcpRowState> ioStates) {
    Impl&     s = *impl_;
    LcpResult result;
    const std::size_t n = problem.size > 0 ? static_cast<std::size_t>(problem.size) : 0;
    if (!lcpValidate(problem) || outX.size() != n || (!ioStates.empty() && ioStates.size() != n)) {
        result.status = LcpStatus::InvalidInput;
        return result;
    }
    if (n == 0) {
        return result;
    }

    // Pivots of the attempts before the last load: a guess that did not hold, the frozen boxes.
    int  earlierPivots = 0;
    // Whether the last passes started from a guess: only a guess can lead them astray, and a
    // failed cold start is not tried again. Until the frozen boxes, ioStates holds the caller's.
    bool guessed = false;
    const bool tryFrozenBoxes =
        !problem.findex.empty() && !ioStates.empty() && s.settings.frictionBoxPasses > 0;

    s.load(problem, ioStates);
    LcpStatus status = LcpStatus::Solved;
    if (!s.settle(tryFrozenBoxes, status, result.couplingPasses)) {
        // The guess did not hold: look for the pattern with frozen boxes, then start over.
        earlierPivots += s.pivots;
        s.saveGuess(outX, ioStates);
        const LcpResult frozen = solveWithFrozenBoxes(problem, outX, ioStates);
        if (frozen.status == LcpStatus::Solved) {
            LcpResult settled = frozen;
            settled.pivots += earlierPivots;
            return settled;
        }
        earlierPivots += frozen.pivots;
        guessed = true;  // the last pattern of the frozen boxes, whatever the caller's was
        s.load(problem, ioStates);
        s.settle(false, status, result.couplingPasses);
    }
    if (status == LcpStatus::NotConverged &&
        (guessed || std::any_of(ioStates.begin(), ioStates.end(),
                                [](LcpRowState state) { return state != LcpRowState::Unknown; }))) {
        // A guess can lead the coupled passes into a cycle that a cold start, normals first and
        // friction after them, never enters; only failed solves pay for the try.
        earlierPivots += s.pivots;
        s.load(problem, {});
        const int maxPasses = std::exchange(s.settings.maxCouplingPasses,
                                            std::min(kColdStartPasses, s.settings.maxCouplingPasses));
        s.settle(false, status, result.couplingPasses);
        s.settings.maxCouplingPasses = maxPasses;
    }
    s.finish(problem, outX, ioStates, result, status);
    result.pivots += earlierPivots;
    return result;
}

bool LcpExactSolver::Impl::settle(bool stopIfFirstFails, LcpStatus& status, int& passes) {
    status = LcpStatus::Solved;
    for (int pass = 1;; ++pass) {
        passes = pass;
        solvePattern(true);
        bool checked = false;  // the last check found nothing wrong with the current x
        bool found = false;    // the last check's pending rows are those of the current x
        if (pass == 1) {
            // Single principal pivots on the worst row, while the number of wrong rows does not
            // grow: a nearly right warm start is repaired in about one pivot per changed row.
            int previous = n + 1;
            for (int round = 0; round < kMaxFlipRounds; ++round) {
                const int wrong = checkPattern(true, true);
                if (wrong == 0) {
                    checked = pending.empty();
                    found = true;
                    break;
                }
                solvePattern(true);
                if (wrong > previous) {
                    break;
                }
                previous = wrong;
            }
        }
        // A check that found rows but none to flip changed nothing: its rows are released as
        // found, not looked for again.
        int released = 0;
        if (found && !checked) {
            releaseAll(pending);
            released = static_cast<int>(pending.size());
        } else if (!checked) {
            released = checkPattern(true, false);
        }
        if (released == 0 && nP == n) {
            return true;
        }
        if (stopIfFirstFails) {
            return false;
        }
        if (pass >= settings.maxCouplingPasses) {
            status = LcpStatus::NotConverged;  // released rows stay unprocessed: reported failed
            return true;
        }
        while (released > 0) {
            solvePattern(true);
            released = checkPattern(true, false);
        }
        pivotUnprocessed(pass);
        if (pivotLimitHit) {
            solvePattern(false);
            status = LcpStatus::PivotLimit;
            return true;
        }
    }
}

// Status Solved when the boxes settle, or when the coupled passes started from a frozen pass's
// pattern settle within kCoupledTryPasses (residual against the coupled problem either way);
// otherwise NotConverged with ioStates holding the last pattern, and the pivots spent.
//
// The plain iteration (boxes = mu·|x_normal| of the last answer) often cycles between patterns
// on a tumbling figure's landing: the map from normals to normals is steep there. Whenever the
// boxes' largest change grows, the boxes are damped further: each pass's box is a blend of the
// last box and mu·|x_normal|, the new one's weight halved down to kMinBoxBlend, which turns the
// cycles into a contraction. Damped boxes settle only linearly, but the pattern settles long
// before they do: a pass that keeps its pattern has most likely found the coupled one, which the
// coupled passes then solve exactly; if they do not settle, the frozen passes go on.
LcpResult LcpExactSolver::solveWithFrozenBoxes(const LcpProblem& problem, std::span<Real> x,
                                               std::span<LcpRowState> ioStates) {
    Impl&             s = *impl_;
    const std::size_t n = static_cast<std::size_t>(problem.size);
    s.boxLo.assign(problem.lo.begin(), problem.lo.end());
    s.boxHi.assign(problem.hi.begin(), problem.hi.end());
    s.boxStates.assign(ioStates.begin(), ioStates.end());
    LcpProblem frozen = problem;
    frozen.lo = s.boxLo;
    frozen.hi = s.boxHi;
    frozen.findex = {};
    frozen.mu = {};
    LcpResult result;
    result.status = LcpStatus::NotConverged;
    Real previousChange = kLcpInfinity;
    Real blend = 1;
    bool loaded = false;  // the frozen problem is the one in s (a coupled try replaces it)
    bool tried = false;   // the last pass's pattern was tried coupled, and did not hold
    for (int pass = 0; pass <= s.settings.frictionBoxPasses; ++pass) {
        Real change = 0;
        Real largest = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const int from = problem.findex[i];
            if (from < 0) {
                continue;
            }
            const Real normal = x[static_cast<std::size_t>(from)];
            const Real box = problem.mu[i] * (std::isfinite(normal) ? std::abs(normal) : Real(0));
            change = std::max(change, std::abs(box - s.boxHi[i]));
            largest = std::max(largest, box);
            const Real next = pass == 0 ? box : blend * box + (1 - blend) * s.boxHi[i];
            s.boxLo[i] = -next;
            s.boxHi[i] = next;
        }
        if (pass > 0 && change <= s.settings.tolerance * std::max(Real(1), largest)) {
            std::copy(s.boxStates.begin(), s.boxStates.end(), ioStates.begin());
            result.status = LcpStatus::Solved;
            result.residual = s.settings.computeResidual ? lcpResidual(problem, x, s.settings.cfm) : 0;
            return result;
        }
        if (pass == s.settings.frictionBoxPasses) {
            break;
        }
        if (pass > 0 && change > previousChange) {
            blend = std::max(blend / 2, kMinBoxBlend);
        }
        previousChange = change;
        s.boxPattern.assign(s.boxStates.begin(), s.boxStates.end());
        // A pass after a frozen one goes on from its factorised pattern with the new boxes: the
        // pattern that loading its states again would give (in another position order, so ties
        // may pivot differently), without a copy of A and a factorisation from scratch.
        if (loaded) {
            s.rebox(s.boxLo, s.boxHi);
        } else {
            s.load(frozen, s.boxStates);
            loaded = true;
        }
        LcpResult r;
        LcpStatus status = LcpStatus::Solved;
        s.settle(false, status, r.couplingPasses);
        // The frozen problems' residuals are not the answer's: only the final one is computed.
        const bool residual = std::exchange(s.settings.computeResidual, false);
        s.finish(frozen, x, s.boxStates, r, status);
        s.settings.computeResidual = residual;
        result.pivots += r.pivots;
        if (r.status != LcpStatus::Solved) {
            break;
        }
        if (s.boxPattern != s.boxStates) {
            tried = false;
        } else if (!tried) {
            if (tryCoupled(s, problem, x, ioStates, result)) {
                return result;
            }
            loaded = false;
            tried = true;
        }
    }
    std::copy(s.boxStates.begin(), s.boxStates.end(), ioStates.begin());
    return result;
}

}  // namespace af
