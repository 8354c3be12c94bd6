#pragma once
// A simulated figure: rigid bodies and joints built from a Figure, advanced by a fixed step.
//
// One step (of settings.timeStep, split into substeps):
//  1. springs add their forces; every body's velocity is predicted with gravity and the
//     external forces (integrateVelocity);
//  2. the collision world finds the contact manifolds of the predicted motion (speculative:
//     pairs closer than what the step can close get points, see contactMargin); awake bodies
//     joined by joints, contact points or the drag form islands, and each island runs 3–6 on
//     its own contiguous copy of its bodies (two figures apart never share a solve); every joint
//     writes its rows (equality, limits, joint friction), every contact point its normal and
//     friction rows, and the drag, if any, its rows (src/dynamics/row_source.h);
//  3. the velocity LCP  J M⁻¹ Jᵀ λ = target − J v + w  is solved (exact pivoting, the tree
//     solver or PGS, warm started from the previous step's pattern and impulses) and the
//     impulses applied. Each row's target is raised by its CFM times its previous impulse: a
//     row's softness lets it yield CFM·λ every step, which a body resting on its rows would
//     otherwise carry as velocity and lose as position each step;
//  4. positions are integrated with the new velocities, then air friction;
//  5. SHAKE closes the drift the step's own motion opened in the joints, with impulses along
//     the start-of-step constraint directions that move positions and velocities together
//     (symplectic: a pendulum keeps its energy), when that move is well conditioned;
//  6. position projection: the rows are written again at the new poses and J M⁻¹ Jᵀ Δ = −C is
//     solved for displacements (not velocities), until converged, for what is left:
//     older joint errors, limit and contact penetration. Correcting them by moving positions
//     instead of adding Baumgarte velocity keeps a resting figure from gaining energy.
//  7. the guard: figures that touched in the step are judged together; where the step left a
//     NaN or an infinity, or far more kinetic energy than they had and gravity, their springs
//     and the applied forces could supply, their bodies are put back where they were before the
//     step, still, and the step's report names them (StepReport::restored). Others go on. A
//     figure put back rests there unless a joint of it is open there (a hostile start): then it
//     stays awake to close it, and is reported stuck if it cannot.
//
// Rest and wake (docs/doom-physics.md §4.11, rest.h): after each step every awake figure's
// RestMonitor is asked. A figure still but with a joint open or a contact deep (beyond
// kStuckJointError, kStuckPenetration) does not rest: it is stuck, and the step's report says so
// (StepReport::stuck). Figures that touch each other form a group that rests only when all of
// them would, and then rests together; a resting figure's bodies have zero velocity, are not
// integrated and cost no solver time. A resting figure wakes, with everything it touches, when
// an awake body touches it, when an impulse above impulseThreshold or any force is applied to
// it, when the caller says so (wakeFigure, after setting velocities or poses), or when a static
// shape is removed.
// Deterministic: the same inputs give bit-identical results.
//
// The world is changed only through its calls, which keep its caches, contacts and rest in step
// with what they change: the bodies and the collision world are read-only here. The solvers' own
// knobs and counters, rows written by the caller and writable bodies are internal
// (src/dynamics/world_access.h).

#include "af/collision/collision_world.h"
#include "af/dynamics/contact.h"
#include "af/dynamics/joints.h"
#include "af/dynamics/rest.h"
#include "af/dynamics/rigid_body.h"
#include "af/figure/figure.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace af {

namespace detail {
struct WorldAccess;  // src/dynamics/world_access.h: for tests and benchmarks, never for embedders
}

// Exact: the dense pivoting solve of all rows. Tree (the default): the same answer, within the
// same tolerance, through the sparse path (src/dynamics/sparse_lcp.h: the last step's pattern,
// a sparse factorisation, a small dense core for the rows it gets wrong), then the linear-time
// factorisation of the joint trees (src/dynamics/tree_solver.h), then the dense solve, each
// taking over when the one before gives up. It is the default because it costs a fraction of
// Exact (our humanoid dropped on the default map: 0.85 against 1.6 ms a step). Pgs: projected
// Gauss–Seidel on the rows (velocities only). The position projection uses the tree solver
// with Tree, the dense pivoting solve otherwise. Islands beyond exactRowLimit rows (piles of
// figures) are solved figure by figure with Tree (each figure's rows exactly, the contacts
// between figures iterated: docs/solver.md), by PGS over all rows otherwise.
enum class SolverKind { Exact, Tree, Pgs };

struct WorldSettings {
    Vec3 gravity = Vec3(0, 0, -1066);  // Doom's g_gravity, units/s²
    Real timeStep = Real(1) / 60;      // s
    int substeps = 1;
    SolverKind solver = SolverKind::Tree;
    // An island whose pivoting solve would have more rows than this is solved figure by figure
    // with Tree, by PGS on its rows otherwise (velocities and positions): a pivot costs O(rows²)
    // and the dense matrices O(rows²) memory, so a pile of many figures would take seconds per
    // step. The rows counted are all of them for Exact, those outside the joints' equality rows
    // for Tree (the Schur complement's). One figure's island (our humanoid: up to ~300 rows
    // tumbling on the floor) stays exact; with Tree, two figures touching do too.
    std::size_t exactRowLimit = 400;
    IntegrationSettings integration;
    JointRowSettings rows;
    // Projection passes per step, at most; they stop once no row is violated by more than
    // positionTolerance (length units, or radians for angular rows). 0 turns projection off.
    // 16 because a whipping chain's end links turn ~1.4 rad per step, and from there 8 passes
    // left up to 0.9 units of joint error, which SHAKE then refused to close and which fed energy
    // into the chain; 16 close them to 1e-10. Calmer steps (the bench's) stop after a few passes.
    int positionIterations = 16;
    Real positionTolerance = 1e-10;
    // Contacts: a pair gets contact points while closer than contactMargin plus the distance
    // the two can close on each other within the step (speculative contacts: a fast body is
    // stopped at the surface it would pass through within the step, so nothing tunnels through
    // a thin floor; see CollisionWorld::findContacts).
    Real contactMargin = 1;  // units
    ContactSettings contact;
    CollisionSettings collision;
    // Rest: figures are tested after every step (rest.h) unless this is off. Impulses smaller
    // than impulseThreshold are ignored, as Doom ignores them, so they cannot wake a figure.
    bool comeToRest = true;
    Real impulseThreshold = 500;  // mass units · units/s (Doom's IMPULSE_THRESHOLD)
    // Threads that step independent islands (figures that do not touch) side by side, the
    // calling thread one of them; 1 to 256. An island stepped alone (a pile) shares out the
    // exact solves of its figures instead. Each island is solved alone whatever the count, so a
    // world steps to the same bits on any number of threads. While a drag or extra rows are
    // active the islands are stepped one after another (their rows read the world's bodies).
    int threads = 1;
};

// A figure in a world. Ids are never reused: an id names the same figure while others are spawned
// and removed, and a removed figure's id is refused (std::invalid_argument) by every call.
struct FigureId {
    int value = -1;
    friend auto operator<=>(FigureId, FigureId) = default;
};

// Why a step's motion of a figure was found invalid (docs/solver.md, "Invalid motion").
enum class InvalidMotion : std::uint8_t {
    NonFinite,   // a NaN or an infinity in a pose or a velocity
    EnergyGain,  // kinetic energy beyond twice what the figure had and the step could supply
};

// A figure whose motion a step made invalid: it was put back where it was before that step, with
// zero velocities and its drag let go, at rest unless a joint of it is open there (see step 7);
// figures it did not touch in the step were not changed. (Bodies of
// no figure, from the bodies-and-joints constructor, are put back alike, under figure value −1.)
struct RestoredFigure {
    FigureId figure;
    InvalidMotion reason = InvalidMotion::NonFinite;
    Real energy = 0;  // EnergyGain: the kinetic and spring energy the step ended with
    Real budget = 0;  // EnergyGain: what it had before and the step could supply
};

// A figure that came to a standstill where it cannot be: a joint open or a contact deep, held
// there (a limb spawned inside a brush with its joints pulled apart, a figure wedged into
// another). It is not put to rest, since resting would freeze the error; it stays awake, and
// rests as soon as it is free and still.
// A still figure is stuck when a joint of it is open wider than kStuckJointError (a closed
// joint's error is rounding, 1e-10 units) or a contact of it deeper than kStuckPenetration (twice
// the default contact slop, which the projection leaves alone).
inline constexpr Real kStuckJointError = 0.05;
inline constexpr Real kStuckPenetration = 0.1;

struct StuckFigure {
    FigureId figure;
    Real jointError = 0;   // its widest joint gap, units
    Real penetration = 0;  // its deepest contact, units
};

// What the last step did.
struct StepReport {
    int rows = 0;       // velocity rows of the last substep
    Real residual = 0;  // LCP residual of the last velocity solve
    int failures = 0;   // solves of this step that did not report Solved
    std::vector<RestoredFigure> restored;  // each reported in the step that found it, once
    std::vector<StuckFigure> stuck;  // reported in the step it stopped stuck, once until it frees
};

// What the last step's velocity solve applied at one contact point (World::contactImpulses), on
// body A; body B took the opposite. An impulse, not a force: mass units · units/s.
struct ContactImpulse {
    Real normal = 0;               // along the manifold's normal (B towards A), ≥ 0: it only pushes
    Vec3 friction = Vec3::Zero();  // world, in the contact plane
};

// A body of a figure: the figure and the body's index in its definition.
struct BodyRef {
    FigureId figure;
    int body = 0;
};

// Doom's mouse drag (docs/doom-physics.md §5.2): every step the grabbed point's velocity is made
// `damping` · its velocity + (1 − damping) · the velocity that closes its gap to `target` in one
// step, by three rows solved with the figure (so that a hand carrying a whole figure still gets
// there; Doom sets the body's velocities instead, and the figure's weight drags the hand down).
struct Drag {
    BodyRef body;
    Vec3 localPoint = Vec3::Zero();  // the grabbed point, body frame (relative to the centre of mass)
    Vec3 target = Vec3::Zero();      // world
    Real damping = 0.5;              // g_dragDamping, in [0, 1)
};

class World {
public:
    explicit World(const WorldSettings& settings = {});
    explicit World(const Figure& figure, const WorldSettings& settings = {});
    // Bodies and joints without collision shapes: they collide with nothing.
    World(std::vector<RigidBody> bodies, std::vector<Joint> joints, const WorldSettings& settings = {});
    ~World();
    World(World&&) noexcept;
    World& operator=(World&&) noexcept;

    // Spawns an instance of `definition` (a figure built once, usually in model space, and shared by
    // every instance) moved by `placement` (docs/figures.md §3.9), at rest-free start: awake, with
    // zero velocities. Its bodies follow those already in the world.
    FigureId spawn(std::shared_ptr<const Figure> definition, const RigidPose& placement = {});
    // Doom's StartFromCurrentPose (docs/figures.md §3.9): the bodies placed where the skeleton
    // `pose` (world space, the definition's joints) puts them, and, given the pose `dt` seconds
    // before, the velocities that carry each body from there to here.
    FigureId spawnFromPose(std::shared_ptr<const Figure> definition, const Skeleton& pose,
                           const Skeleton* earlierPose = nullptr, Real dt = 0);
    // A copy of `figure`, as placed.
    FigureId addFigure(const Figure& figure);
    // Removes a figure, its binds and its drag; what touched it wakes.
    void remove(FigureId figure);
    bool contains(FigureId figure) const;
    std::vector<FigureId> figureIds() const;  // the figures in the world, in spawn order
    const Figure& definition(FigureId figure) const;

    // Poses and velocities, per figure; body i is the definition's body i.
    std::vector<RigidPose> bodyPoses(FigureId figure) const;
    const RigidBody& body(BodyRef body) const;
    // The skeleton the figure's bodies drive, world space (poseSkeleton).
    Skeleton skeleton(FigureId figure) const;
    // Puts every body of the figure at the given pose, at rest-free start: zero velocities, awake,
    // and wakes what touched it. Non-finite poses are refused (std::invalid_argument).
    void setPose(FigureId figure, std::span<const RigidPose> bodyPoses);
    // A body's velocities (linear at the centre of mass); wakes its figure.
    void setVelocity(BodyRef body, const Vec3& linear, const Vec3& angular);

    // An impulse (mass units · units/s) at a world point of a body: changes its velocities now,
    // and wakes its figure; ignored when smaller than impulseThreshold.
    void applyImpulse(BodyRef body, const Vec3& worldPoint, const Vec3& impulse);
    // A force (mass units · units/s²) at a world point, for the next step only; wakes the figure.
    void addForce(BodyRef body, const Vec3& worldPoint, const Vec3& force);
    // The drag, if any (Drag above); starting or moving it wakes the figure.
    void setDrag(const Drag& drag);
    void clearDrag();
    const std::optional<Drag>& drag() const;
    // Doom's bindRagdoll: a ball-and-socket joint holding a body's point at `worldAnchor` (where it
    // is now, or the body is pulled there); unbind removes every bind of the figure.
    void bind(BodyRef body, const Vec3& worldAnchor);
    void unbind(FigureId figure);
    int bindCount(FigureId figure) const;

    // The static world: planes and brushes (world space), numbered together, as the collision
    // world numbers them (BodyContact::staticShape). Adding one wakes nothing: a figure resting
    // where the shape appears stays as it lies (removeStatic, below, wakes every figure).
    int addStaticPlane(const Plane& plane, ContentsMask contents = contents::Solid);
    int addStaticBrush(const Polytope& worldShape, ContentsMask contents = contents::Solid);
    // The collision world, for queries: its shapes, filters and rules.
    const CollisionWorld& collision() const;

    void step();

    // Rest and wake (see the top of this file).
    bool figureAtRest(FigureId figure) const;
    bool atRest() const;  // every figure at rest (false for a world without figures)
    void wakeFigure(FigureId figure);
    // Puts a figure to rest where it is (zero velocities), as Doom does to a map's figure with
    // `nodrop`; anything that touches or pushes it wakes it as usual.
    void putToRest(FigureId figure);
    // Removes a static shape of the collision world and wakes every figure (what lay on it falls).
    void removeStatic(int staticShape);

    // Contact manifolds of the last step, looked for again at the poses it ended with (what
    // touches there; the step's own solve used those found at its start poses, with a margin).
    const std::vector<BodyContact>& contacts() const;
    // Deepest penetration of the last step's contact points at the current poses (0 if none).
    Real maxPenetration() const;
    // The impulse each point of contacts() took in the last step's velocity solve (its last
    // substep's), manifold by manifold in their order, each manifold's points in theirs: a box
    // of mass m resting on the floor takes m·|g|·timeStep/substeps over its points. A point that
    // solve did not have reports zero: one found only at the step's end poses, or apart and left
    // out of it. Resting figures are not solved, and their contacts leave contacts() after the
    // step they came to rest in. Friction is along the rows' directions (tangents of the normal,
    // or body A's frictionDirection as A is turned now).
    std::vector<ContactImpulse> contactImpulses() const;

    // Every body of the world in one array (figures in spawn order), and the joints; a body's
    // index changes when a figure before it is removed.
    const std::vector<RigidBody>& bodies() const;
    const std::vector<Joint>& joints() const;
    struct FigureRange {
        int firstBody = 0, bodyCount = 0, firstJoint = 0, jointCount = 0;
    };
    FigureRange range(FigureId figure) const;
    // The figure a body of bodies() belongs to (value -1 for a body of no figure).
    FigureId figureOf(int body) const;
    // Body-index versions of the calls above; a body of no figure (World's bodies-and-joints
    // constructor) has no figure to wake.
    void setVelocity(int body, const Vec3& linear, const Vec3& angular);
    void applyImpulse(int body, const Vec3& worldPoint, const Vec3& impulse);
    void addForce(int body, const Vec3& worldPoint, const Vec3& force);

    const WorldSettings& settings() const;
    // New settings from the next step on (the console's af_* cvars): gravity, time step, limits,
    // friction, caps, collision rules, … Every figure wakes. A non-finite or out-of-range value is
    // refused (std::invalid_argument) and the world is left as it was; the constructor refuses
    // such settings alike.
    void setSettings(const WorldSettings& settings);
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
    friend struct detail::WorldAccess;
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace af
