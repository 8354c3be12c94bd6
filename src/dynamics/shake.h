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
// than the drift it closes, and its velocity feeds the motion that caused it; at fast turns its
// velocity can also add kinetic energy the next step does not take back. Such a move is refused:
// see Island::closeDrift and keptKineticEnergy().

#include "joint_errors.h"
#include "joint_rows.h"
#include "row_system.h"

#include <span>
#include <vector>

namespace af {

class ShakeCorrection {
public:
    // Remembers the equality rows of the velocity solve and their responses M⁻¹J₀ᵀ, and the
    // limit rows with hold[i] != 0 (empty: none), which are closed to min(C₀, 0), where the
    // velocity solve took them. Moved along the equality rows alone, SHAKE turned a resting
    // ankle 8e-3 rad past its limit every step of the bench drop, which the projection then took
    // back. A held limit's share of the move changes no velocity: given back as velocity it
    // bounces the body off the limit (16 ragdolls dropped together gained 0.13 J).
    void capture(const ConstraintRows& rows, const std::vector<JointRowRange>& ranges, const RowSystem& system,
                 std::span<const char> hold = {});

    struct Step {
        Real drift = 0;  // largest joint drift before the step, length units
        Real move = 0;   // largest move of any body point (centre move + turn × gyration radius)
    };

    // The largest drift of the joints since `start` (rows and ranges as capture takes them):
    // |error now − error at start| over the equality rows, with `errors` measured at the moved
    // poses (writeJointErrors, same joints), as apply measures it after capture(start).
    static Real drift(const ConstraintRows& start, const std::vector<JointRowRange>& startRanges,
                      std::span<const RowError> errors, const std::vector<JointRowRange>& ranges);
    // The same from rows written at the moved poses.
    static Real drift(const ConstraintRows& start, const std::vector<JointRowRange>& startRanges,
                      const ConstraintRows& rows, const std::vector<JointRowRange>& ranges);

    // With `rows` written at the moved poses (same joints, so the same equality rows in the
    // same order; a captured limit row must be there too, or nothing is moved and the move is
    // reported as +∞), one Newton step: moves the bodies and changes their velocities by move / dt.
    // The first step after a capture builds and factorises K; later ones reuse it. A drift of
    // at most `closed` (length units) is left as it is: nothing is factorised or moved (a
    // resting figure). If K is singular (a zero pivot: joints repeating each other's rows),
    // nothing is moved and the move is reported as +∞, which no caller keeps.
    Step apply(const ConstraintRows& rows, const std::vector<JointRowRange>& ranges, std::span<RigidBody> bodies,
               Real dt, Real closed);
    // A later Newton step with the factors of K apply() left, on the errors measured at the moved
    // poses (writeJointErrors, same joints) instead of written rows: it needs no Jacobian. Moves
    // any drift that is not 0. A captured limit row counts as the same limit when the joint
    // still has it (apply() checked its turn, and the bodies have moved since by that step's
    // remainder). Without factors (no apply() since the capture, or one that moved nothing),
    // reports +∞.
    Step applyAgain(std::span<const RowError> errors, const std::vector<JointRowRange>& ranges, std::span<RigidBody> bodies,
                    Real dt);

    // The kinetic energy the bodies keep when their velocities are projected M-orthogonally onto
    // the tangent space of the equality rows capture() took (J v = 0; capture them from rows
    // written at the bodies' poses, with their responses): what a velocity solve on those rows
    // alone leaves of the bodies' motion. +∞ if K is singular. Factorises K afresh: apply() and
    // applyAgain() must not follow before the next capture.
    Real keptKineticEnergy(const ConstraintRows& rows, const std::vector<JointRowRange>& ranges,
                           std::span<const RigidBody> bodies);

private:
    // K = J₁ M⁻¹ J₀ᵀ couples two joints' rows only when the joints share a body. Eliminating the
    // joints in a perfect order (a joint at the world or at a leaf body first: its neighbours
    // all share its other body and are already coupled) leaves that pattern without fill for a
    // figure whose joints form a tree, so K is factorised in time linear in the joints. Loops
    // get the fill they need. Rows of joints that share no body (through other joints) form
    // separate blocks, each factorised on its own, with its own dense storage.
    struct Range {
        int start = 0, size = 0;  // positions within a block
    };
    struct Group {                // one joint's equality rows
        int first = 0, size = 0;  // in the captured rows
        int bodyA = kWorldBody, bodyB = kWorldBody;
        int block = 0;
        Range at;                         // where its rows sit in its block
        int laterBegin = 0, laterEnd = 0;  // its neighbours when eliminated, in later_
        int rowsBegin = 0, rowsEnd = 0;    // its rows, then those neighbours', in laterRows_
    };
    struct Block {
        int firstRow = 0, size = 0;      // positions in order_
        int firstGroup = 0, groups = 0;  // positions in eliminated_
        std::vector<Real> k;             // size × size, row-major; only the pattern is used
    };
    void findStructure();
    void layOut();
    void orderGroups(int bodies);
    bool simplicial(int group);
    void eliminate(int group);
    template <class ErrorOf, class SameLimit>
    bool measureDrift(const std::vector<JointRowRange>& ranges, ErrorOf errorOf, SameLimit sameLimit, Step& step);
    void factorise(const ConstraintRows& rows);
    void solveLambda();
    void sumResponses(std::size_t bodies);
    void move(std::span<RigidBody> bodies, Real dt, Step& step);
    void fillBlock(const Block& block, const ConstraintRows& rows, std::vector<Real>& k) const;
    bool factorBlock(const Block& block, std::vector<Real>& k) const;
    void solveBlock(const Block& block, const std::vector<Real>& k, Real* y) const;
    // The rows (places in g's block) that row t of group g couples to later in the order: the
    // rest of its own rows, then its later neighbours' (the LU's and the solve's inner loops).
    // One flat list per group, made with the order: the loops read the places from it instead
    // of walking the neighbours' ranges (bench ragdoll: factorBlock 81k -> 57k instructions,
    // solveBlock 22k -> 12k).
    std::span<const int> laterRowsOf(const Group& g, int t) const {
        return {laterRows_.data() + g.rowsBegin + t + 1, static_cast<std::size_t>(g.rowsEnd - g.rowsBegin - t - 1)};
    }

    // What SHAKE reads of a captured row (a whole row is three times the size to copy).
    struct StartRow {
        int bodyA = kWorldBody, bodyB = kWorldBody;
        bool limit = false;  // a held limit row
        Vec3 angularA = Vec3::Zero();
        Real error = 0;      // C₀, a limit's min(C₀, 0)
    };
    std::vector<StartRow> start_;
    bool heldLimits_ = false;  // any of start_
    std::vector<int> offset_;  // per captured row: its place in its joint's range
    std::vector<RowResponse> responses_;
    std::vector<Group> groups_;
    std::vector<std::vector<int>> adjacent_;  // per group: groups sharing a body, and fill
    std::vector<int> eliminated_;        // groups in elimination order, grouped by block
    std::vector<int> later_;
    std::vector<int> laterRows_;  // per group: see Group::rowsBegin
    std::vector<int> stamp_, parent_, blockOfRoot_, bodyGroups_, bodyGroupsBegin_, pending_;
    std::vector<char> done_;
    int stampValue_ = 0;
    std::vector<Block> blocks_;
    std::size_t blockCount_ = 0;
    std::vector<int> order_;           // captured rows, block by block in elimination order
    std::vector<std::size_t> nowRow_;  // per captured row: its index in the rows given to apply
    std::vector<Real> drift_, lambda_, y_;
    std::vector<Vec3> linear_, angular_;
    std::vector<Vec3> limitLinear_, limitAngular_;
    bool structured_ = false;  // groups_, the blocks and the order are those of the last capture
    bool factorised_ = false;  // the blocks hold the factors of K of this capture
    bool singular_ = false;    // a zero pivot: no move can be trusted
};

}  // namespace af
