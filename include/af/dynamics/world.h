#pragma once
// A simulated figure: rigid bodies and joints built from a Figure, advanced by a fixed step.
//
// One step (of settings.timeStep, split into substeps):
//  1. springs add their forces; every body's velocity is predicted with gravity and the
//     external forces (integrateVelocity);
//  2. every joint writes its rows (equality, limits, joint friction), and the contact source,
//     if any, adds contact rows;
//  3. the velocity LCP  J M⁻¹ Jᵀ λ = target − J v + w  is solved (exact pivoting or PGS, warm
//     started from the previous step's pattern) and the impulses applied;
//  4. positions are integrated with the new velocities, then air friction;
//  5. SHAKE closes the drift the step's own motion opened in the joints, with impulses along
//     the start-of-step constraint directions that move positions and velocities together
//     (symplectic: a pendulum keeps its energy), when that move is well conditioned;
//  6. position projection: the rows are written again at the new poses and J M⁻¹ Jᵀ Δ = −C is
//     solved for displacements (not velocities), until converged, for what is left:
//     older joint errors, limit and contact penetration. Correcting them by moving positions
//     instead of adding Baumgarte velocity keeps a resting figure from gaining energy.
// Deterministic: the same inputs give bit-identical results.

#include "af/dynamics/constraint_row.h"
#include "af/dynamics/joints.h"
#include "af/dynamics/lcp.h"
#include "af/dynamics/rigid_body.h"
#include "af/figure/figure.h"

#include <functional>
#include <memory>
#include <span>
#include <vector>

namespace af {

enum class SolverKind { Exact, Pgs };

struct WorldSettings {
    Vec3 gravity = Vec3(0, 0, -1066);  // Doom's g_gravity, units/s²
    Real timeStep = Real(1) / 60;      // s
    int substeps = 1;
    SolverKind solver = SolverKind::Exact;
    LcpExactSettings exact;
    LcpPgsSettings pgs;
    IntegrationSettings integration;
    JointRowSettings rows;
    // Projection passes per step, at most; they stop once no row is violated by more than
    // positionTolerance (length units, or radians for angular rows). 0 turns projection off.
    int positionIterations = 8;
    Real positionTolerance = 1e-10;
};

// What the last step did.
struct StepReport {
    int rows = 0;                  // velocity rows of the last substep
    int pivots = 0;                // exact solver: pivots of the last velocity solve
    int iterations = 0;            // PGS: sweeps of the last velocity solve
    Real residual = 0;             // LCP residual of the last velocity solve
    int failures = 0;              // solves of this step that did not report Solved
    int shakeRefusals = 0;         // substeps whose SHAKE correction was refused (world.cpp)
};

// Appends rows for the current step (hand-made contacts until collision exists).
using RowSource = std::function<void(std::span<const RigidBody>, ConstraintRows&)>;

class World {
public:
    explicit World(const Figure& figure, const WorldSettings& settings = {});
    World(std::vector<RigidBody> bodies, std::vector<Joint> joints, const WorldSettings& settings = {});
    ~World();
    World(World&&) noexcept;
    World& operator=(World&&) noexcept;

    void step();
    void setContactSource(RowSource source);

    std::vector<RigidBody>& bodies();
    const std::vector<RigidBody>& bodies() const;
    const std::vector<Joint>& joints() const;
    const WorldSettings& settings() const;
    Real time() const;
    const StepReport& lastStep() const;
    int solverFailures() const;  // over all steps

    // Largest distance between two bodies' copies of a joint's anchor (and the like, see
    // jointError), and largest limit violation in degrees, at the current poses.
    Real maxJointError() const;
    Real maxLimitViolationDegrees() const;
    Real kineticEnergy() const;
    std::vector<RigidPose> bodyPoses() const;

private:
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace af
