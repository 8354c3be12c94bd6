#pragma once
// The fast path of an island's constraint solve: the boxed LCP of lcp.h on the rows
// J M⁻¹ Jᵀ of constraint_row.h, solved by guessing which rows are free and which sit
// at a bound (the previous step's answer: a resting figure keeps its pattern), solving the free
// rows' equations with the sparse factorisation of sparse_factor.h (time linear in the bodies for
// a figure on the ground), and correcting the guess where it was wrong: free rows beyond a bound
// go to it, clamped rows pulling the wrong way are freed. The trial, the guess's pattern, is
// solved exactly, friction coupling included: a sliding friction row's impulse is μ times its
// normal's, solved together with the free rows (see solvePattern).
//
// No matrix of all rows is ever formed: A's products go through the bodies (M⁻¹Jᵀ per row).
// The answer is accepted only when every row is complementary within the tolerance. Before any
// trial the guess's own impulses are checked (a figure at rest meets its last problem again and
// keeps them without factorising). When the trial finds rows wrong, they are solved as a dense
// LCP on their Schur complement by the pivoting solver (sparse_core.cpp), together with every row
// boxed by fixed bounds (joint friction, whose last states are no guess), and the rows its answer
// finds wrong outside it join it; if that core grows too large, the solve says so and the caller
// falls back to its other solvers.

#include "dynamics/lcp_internal.h"
#include "lcp.h"
#include "sparse_factor.h"

#include <span>
#include <vector>

namespace af {

struct SparseLcpResult {
    LcpStatus status = LcpStatus::Solved;  // NotConverged: no answer, fall back; InvalidInput:
                                           // rows the factorisation cannot take (see analyse)
    int trials = 0;                        // 0: the guess's own impulses held, or were refined;
                                           // 1: its pattern was solved (and held, or a core followed)
    bool refined = false;                  // the guess refined with the last answer's factorisation
    int couplingSolves = 0;                // trials with sliding friction rows (solved coupled)
    int coreRows = 0;                      // rows of the dense core, when the trial did not settle
    int coreRounds = 0;                    // times the core was solved (it grows by the rows found wrong)
    int factorisations = 0;
    Real residual = 0;                     // natural residual (lcp.h) of the answer
};

class SparseLcpSolver {
public:
    // Solves the problem's b, bounds, friction coupling and CFM (problem.a is not read) for the
    // rows, whose responses M⁻¹Jᵀ are given. x and states carry the guess in (for an Unknown row:
    // a contact or limit pushes when it is closing, a friction row sticks when its normal
    // pushes) and the answer out; on failure they hold the last trial. The settings are the
    // pivoting solver's: their tolerance is the answer's, and the dense core is solved with them.
    SparseLcpResult solve(std::span<const ConstraintRow> rows, std::span<const RowResponse> responses,
                          const LcpProblem& problem, std::span<const RigidBody> bodies, std::span<Real> x,
                          std::span<LcpRowState> states, const LcpExactSettings& settings);
    // The bodies' velocity change M⁻¹Jᵀx of the answer of the last solve, when it succeeded:
    // every answer is evaluated before it is accepted, which sums it row by row in the order and
    // with the arithmetic of accumulateResponses (row_system.h), so bit for bit its sum (zero
    // without rows).
    std::span<const Vec3> answerLinearChange() const { return linear_; }
    std::span<const Vec3> answerAngularChange() const { return angular_; }

private:
    bool solvePattern(std::span<const ConstraintRow> rows, std::span<const RowResponse> responses,
                      const LcpProblem& problem, std::span<Real> x, std::span<const LcpRowState> states,
                      SparseLcpResult& result);
    void solveFree(std::span<const ConstraintRow> rows, std::span<const RowResponse> responses,
                   std::span<const Real> b, std::span<const Real> x, std::span<Real> out);
    bool refine(std::span<const ConstraintRow> rows, std::span<const RowResponse> responses, const LcpProblem& problem,
                std::span<Real> x, std::span<const LcpRowState> states, Real wTolerance, Real tolerance);
    bool solveSmall(std::size_t k);
    void solveSmallAgain(std::size_t k);
    Real boundValue(const LcpProblem& problem, std::span<const Real> x, std::span<const LcpRowState> states,
                    std::size_t i) const;
    Real slidingSlope(const LcpProblem& problem, std::span<const LcpRowState> states, std::size_t i) const;
    Real xTolerance(std::size_t i, Real tolerance) const;
    bool guessHolds(std::span<const ConstraintRow> rows, std::span<const RowResponse> responses, const LcpProblem& problem,
                    std::span<const Real> x, std::span<const LcpRowState> states, Real wTolerance, Real tolerance);
    int check(std::span<const ConstraintRow> rows, std::span<const RowResponse> responses, const LcpProblem& problem,
              std::span<const Real> x, std::span<const LcpRowState> states, Real wTolerance, Real tolerance);
    SparseLcpResult& finish(std::span<const Real> x, std::span<const LcpRowState> states, SparseLcpResult& result);
    std::size_t markCore(const LcpProblem& problem, std::span<const LcpRowState> states);
    int solveCore(std::span<const ConstraintRow> rows, std::span<const RowResponse> responses, const LcpProblem& problem,
                  std::span<Real> x, std::span<LcpRowState> states, std::span<const LcpRowState> coreGuess,
                  Real wTolerance, const LcpExactSettings& settings, SparseLcpResult& result);
    // The small questions asked of every row, inline: the solver's three files (sparse_lcp.cpp,
    // sparse_pattern.cpp, sparse_core.cpp) ask them in their inner loops.
    static bool clamped(LcpRowState s) { return s == LcpRowState::AtLower || s == LcpRowState::AtUpper; }
    int source(const LcpProblem& problem, std::size_t i) const { return problem.findex.empty() ? -1 : problem.findex[i]; }
    bool sliding(const LcpProblem& problem, std::span<const LcpRowState> states, std::size_t i) const {
        const int s = source(problem, i);
        return s >= 0 && clamped(states[i]) && states[static_cast<std::size_t>(s)] == LcpRowState::Free;
    }
    // A row boxed on both sides by bounds of its own (a joint's friction, ±f·|λ_previous|), which
    // the core always takes (sparse_core.cpp). Inline: asked of every row of every core.
    bool fixedBox(const LcpProblem& problem, std::size_t i) const {
        return problem.hi[i] < kLcpInfinity && problem.lo[i] > -kLcpInfinity && problem.lo[i] < problem.hi[i] &&
               source(problem, i) < 0;
    }
    void bounds(const LcpProblem& problem, std::span<const Real> x);
    void bound(const LcpProblem& problem, std::span<const Real> x, std::size_t i);
    void measureW(std::span<const ConstraintRow> rows, std::span<const RowResponse> responses, const LcpProblem& problem,
                  std::span<const Real> x);
    void velocityChange(std::span<const ConstraintRow> rows, std::span<const RowResponse> responses,
                        std::span<const Real> x, std::span<const std::uint8_t> use);
    // J of the row times the velocity change held in linear_ and angular_ (inline, as above).
    Real along(const ConstraintRow& r) const { return rowAlong(r, linear_, angular_); }

    SparseRowFactor factor_;
    Real boundGap_ = 0;  // of the last solved answer: its rows at a bound, how far off it
    std::size_t lastMiss_ = 0;  // the row where guessHolds last found the guess failing
    bool guessRefused_ = false;  // guessHolds refused the last step's guess
    // factor_, free_, slidingRows_ and the LU of small_ (with smallPivots_) are those of the last
    // answer, found by a trial: a guess in its pattern can be refined with them (refine()).
    bool refinable_ = false;
    bool slidingAnswersKept_ = false;  // slidingAnswers_ belong to factor_ (refine())
    std::vector<Real> slidingAnswers_;
    std::vector<int> smallPivots_;
    std::vector<Real> correction_;
    std::vector<Real> lo_, hi_, w_, rhs_, small_, beta_;
    // Forwarded columns (solvePattern's and the core's, of different sizes in turn): each is
    // written whole before it is read, so growing needs no zeroing (lcp::Workspace).
    lcp::Workspace paths_;
    std::vector<std::uint8_t> free_, use_, reached_, switched_, touched_;
    std::vector<LcpRowState> guessStates_;  // the states the trial started from (solve())
    std::vector<int> pathStart_;  // solveCore: the first variable each path reaches
    std::vector<int> supports_, supportStart_;  // solvePattern: the groups each path reaches
    // The core (sparse_core.cpp): rows whose state the trial could not settle, solved as a dense
    // LCP on their Schur complement with the pivoting solver.
    std::vector<int> core_, coreIndex_;
    std::vector<std::uint8_t> inCore_;
    std::vector<Real> inversePivots_, forwarded_;
    lcp::Workspace scaledPaths_;
    // The last round's core, paths and Schur complement, for the next round of the same solve.
    std::vector<int> lastCore_, lastCoreIndex_, lastPathStart_;
    lcp::Workspace lastPaths_, lastCoreA_, coreA_;
    std::vector<Real> coreB_, coreLo_, coreHi_, coreMu_, coreCfm_, coreX_, zeros_;
    std::vector<int> coreFindex_;
    std::vector<LcpRowState> coreStates_;
    LcpExactSolver coreSolver_;
    std::vector<int> slidingRows_;
    std::vector<int> boundRows_, boundFriction_;  // refine(): its rows at a bound
    std::vector<LcpRowState> next_;
    std::vector<Vec3> linear_, angular_;
};

}  // namespace af
