#pragma once
// SHAKE's correction of the drift a step's own motion opens in the joints.
//
// The velocity solve makes the joint rows hold to first order; bodies then move along straight
// tangents and the joints open by O(dt²). Closing that drift by moving positions alone keeps
// the velocity that carried the bodies off the joints, which the next step then removes: a
// swinging figure loses energy every step. SHAKE (Ryckaert, Ciccotti & Berendsen 1977) closes
// it with impulses along the constraint directions of the START of the step, solving
//     C(q + M⁻¹J₀ᵀΔλ) = C₀
// by Newton's method with the true Jacobian J₁ M⁻¹ J₀ᵀ (not symmetric), and changes the
// velocities by the same move over dt. That is symplectic: a pendulum keeps its energy over
// hundreds of swings.
//
// When J₁ M⁻¹ J₀ᵀ is ill-conditioned (long chains turning fast), Newton's move can be far larger
// than the drift it closes, and its velocity feeds the motion that caused it. Such a move is
// refused: see World's use of accepted().

#include "af/dynamics/joints.h"
#include "row_system.h"

#include <Eigen/Dense>

#include <span>
#include <vector>

namespace af {

class ShakeCorrection {
public:
    // Remembers the equality rows of the velocity solve and their responses M⁻¹J₀ᵀ.
    void capture(const ConstraintRows& rows, const std::vector<JointRowRange>& ranges, const RowSystem& system);

    struct Step {
        Real drift = 0;  // largest joint drift before the step, length units
        Real move = 0;   // largest move of any body point (centre move + turn × gyration radius)
    };

    // With `rows` written at the moved poses (same joints, so the same equality rows in the
    // same order), one Newton step: moves the bodies and changes their velocities by move / dt.
    // The first step after a capture builds and factorises K; later ones reuse it. A drift of
    // at most `closed` (length units) is left as it is: nothing is factorised or moved (a
    // resting figure).
    Step apply(const ConstraintRows& rows, const std::vector<JointRowRange>& ranges, std::span<RigidBody> bodies,
               Real dt, Real closed);

private:
    using Matrix = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>;
    using Vector = Eigen::Matrix<Real, Eigen::Dynamic, 1>;
    // K is block diagonal: rows of joints that share no body (through other joints) do not see
    // each other. Each block (one figure, as a rule) is factorised on its own, so an island of
    // many touching figures costs as many small factorisations, not one large one.
    struct Block {
        int first = 0, size = 0;  // positions in order_
        Matrix k;
        Eigen::PartialPivLU<Matrix> lu;
        Vector rhs;
    };
    void findBlocks();

    std::vector<ConstraintRow> start_;
    std::vector<RowResponse> responses_;
    std::vector<int> order_;         // captured rows grouped by block
    std::vector<int> parent_;        // union-find over bodies
    std::vector<int> blockOfRoot_;
    std::vector<Block> blocks_;
    std::size_t blockCount_ = 0;
    std::vector<int> blockOfRow_;      // per captured row
    std::vector<std::size_t> nowRow_;  // per captured row: its index in the rows given to apply
    Vector drift_, lambda_;
    std::vector<Vec3> linear_, angular_;
    bool factorised_ = false;  // the blocks hold K of this capture
};

}  // namespace af
