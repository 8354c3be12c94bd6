#pragma once
// World's runtime state, shared by the files that implement the step (world.cpp: building and
// queries; world_step.cpp: the step itself).

#include "af/dynamics/world.h"
#include "contact_set.h"
#include "island.h"
#include "row_source.h"
#include "solver_counters.h"
#include "solver_tuning.h"
#include "warm_start.h"
#include "worker_pool.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace af {

// Throws std::invalid_argument, naming `caller`, for settings a world refuses (world_settings.cpp).
void checkSettings(const WorldSettings& settings, const char* caller);

struct World::State {
    WorldSettings settings;
    SolverTuning tuning;  // detail::WorldAccess::setTuning's
    std::vector<RigidBody> bodies;
    std::vector<Joint> joints;
    // Figures by slot, in spawn order; a removal closes the gap (world_figures.cpp). Ids stay.
    std::vector<FigureRange> figures;
    std::vector<std::shared_ptr<const Figure>> definitions;  // per slot
    std::vector<FigureId> ids;                               // per slot
    std::vector<int> slotOfId;                               // per id ever given: its slot, or -1
    // Per joint: the slot of the figure it belongs to (-1: none), and whether it is a bind
    // (World::bind), which follows every figure's own joints.
    std::vector<int> jointFigure;
    std::vector<std::uint8_t> jointIsBind;
    std::optional<Drag> drag;
    RowSource userRows;   // detail::WorldAccess::setContactSource's
    RowSource extraRows;  // what the islands call: userRows and the drag's rows
    Real time = 0;
    StepReport report;
    SolverCounters counters;  // the rest of the last step's report (detail::WorldAccess)
    // settings.threads − 1 workers beside the calling thread (none for 1), and each island's
    // share of the report and counters of one pass over the islands, merged in island order.
    std::unique_ptr<WorkerPool> pool;
    std::vector<StepReport> islandReports;
    std::vector<SolverCounters> islandCounters;
    std::vector<Real> islandSpringWork;  // IslandContext::projectedSpringWork of each island
    void startThreads();
    int failures = 0;
    // The step's guard (world_guard.cpp): the bodies and joint impulses before the step, and the
    // impulse of each body's applied force and torque over it; the figures that touched in it,
    // and the energy of each group of them.
    struct GroupEnergy {
        bool nonFinite = false;
        bool dragged = false;
        Real before = 0, after = 0, work = 0, floor = 0;
    };
    struct BeforeStep {
        std::vector<RigidBody> bodies;
        std::vector<Real> jointImpulses;
        std::vector<Real> forceImpulse, torqueImpulse;
        std::vector<Real> projectedSpringWork;  // per figure slot (and one for bodies of none)
        std::vector<int> touched;  // union-find over figure slots (and one for bodies of none)
        std::vector<GroupEnergy> energy;  // per root of `touched`
    };
    BeforeStep before;

    // Collision: shapes and filters, per-body surface data and reach, this step's contacts.
    CollisionWorld collision;
    std::vector<BodyMaterial> materials;
    std::vector<Real> radius;  // farthest shape vertex from the centre of mass
    std::vector<Real> reach;  // how far a body's turn carries its surface in the step
    std::vector<Vec3> moves;  // how far a body's velocity carries it in the step
    std::vector<RigidPose> poses;
    // This step's manifolds: kept in `manifolds`, or, when a step keeps the last search's or the
    // last settle's whole, read there rather than copied (resting bench ragdoll, every step).
    std::vector<BodyContact> manifolds;
    enum class ManifoldsOf : std::uint8_t { Own, Search, Settled };
    ManifoldsOf manifoldsOf = ManifoldsOf::Own;
    ContactSet contacts;
    // The last search at a step's start and what it found, kept while it covers what a new one
    // would find (see findContacts).
    struct ContactSearch {
        bool known = false;
        std::uint64_t version = 0;  // the collision world's
        std::vector<RigidPose> poses;  // per body: where the search last looked around it
        std::vector<std::uint8_t> awake;
        std::vector<BodyContact> manifolds;
        std::vector<ContactPoint> points;
        std::vector<std::size_t> firstPoint;  // per manifold: its first point in `points`
        std::vector<std::uint8_t> moving;     // scratch: the bodies searched around again
        std::vector<BodyContact> fresh;       // scratch: what that search found
    };
    ContactSearch search;
    bool searchKept = false;  // this step's search was the last one, whole (no body searched around)
    bool islandsOfSearch = false;  // the islands are those of the last search's points (buildIslands)
    // What the last settle found (settleNewContacts), kept likewise.
    struct SettledContacts {
        bool known = false;
        std::vector<RigidPose> poses;
        std::vector<BodyContact> manifolds;
        std::vector<ContactPoint> points;
        Real penetration = 0;  // maxPenetration of the points at the poses they were found at
    };
    SettledContacts settled;

    // Rest: one monitor per figure, and who is awake.
    std::vector<RestMonitor> rest;
    std::vector<std::uint8_t> figureResting;  // per figure
    std::vector<std::uint8_t> figureStuck;    // per figure: reported stuck and not freed since
    std::vector<int> bodyFigure;              // per body: its figure, or -1 (always awake)
    std::vector<std::uint8_t> bodyAwake;      // per body
    std::vector<Vec3> startLinear, startAngular;
    std::vector<BodyMotion> motion;
    std::vector<int> group;  // per figure: union-find parent, figures touching each other

    // Islands of this step (island.h), in the order of their first body; the pool keeps its
    // solvers from step to step, so an island that stays the same keeps its slot.
    std::vector<Island> islands;
    std::size_t islandCount = 0;
    struct IslandMembers {
        std::vector<int> bodies, joints, points;
    };
    std::vector<IslandMembers> members;
    std::vector<int> localOf;  // per body: its index in its island, or kOutsideIsland
    std::vector<int> parent;   // union-find over bodies
    std::vector<int> islandOfRoot;
    ConstraintRows extraScratch;
    WarmStartCache warmStart;  // the last velocity solve of every island

    void addBody(const RigidBody& body, const Polytope& shape, const CollisionFilter& filter,
                 const BodyMaterial& material, int figure);
    FigureId addFigure(const Figure& placed, std::shared_ptr<const Figure> definition);
    int slot(FigureId figure) const;  // throws std::invalid_argument for a figure not in the world
    int bodyIndex(BodyRef body) const;  // likewise, and for a body the figure does not have
    void removeSlot(int slot);
    // After bodies or joints were removed: the figures' ranges anew, and every cache that names
    // bodies, joints or contact points by index forgotten (the next step searches and solves
    // from scratch).
    void renumber();
    StuckFigure stuckness(int figure) const;  // its widest joint gap and deepest contact
    bool stuck(int figure);  // stuck (World::kStuckJointError), and reported in the step's report once
    // Wakes every figure touching a body of `slot` in the last step's contacts.
    void wakeTouching(int slot);
    void wakeDragged();  // a dragged figure never rests
    void writeDragRows(std::span<const RigidBody> all, ConstraintRows& rows) const;
    void useRowSources();

    const std::vector<BodyContact>& found() const {
        return manifoldsOf == ManifoldsOf::Search ? search.manifolds
               : manifoldsOf == ManifoldsOf::Settled ? settled.manifolds : manifolds;
    }
    bool awake(int body) const { return body == kWorldBody || bodyAwake[static_cast<std::size_t>(body)] != 0; }
    void wake(int figure);
    void refreshAwake();
    bool wakeTouched();
    void testRest(Real dt);
    void putToRest(int figure);

    void rememberBeforeStep();
    void joinTouchingForGuard();
    void restoreInvalidMotion();
    void restoreFigure(int slot);  // figures.size(): the bodies of no figure
    // The guard's group of a body: its figure's slot, or figures.size() for a body of no figure.
    int guardGroupOf(int body) const {
        const int f = bodyFigure[static_cast<std::size_t>(body)];
        return f >= 0 ? f : static_cast<int>(figures.size());
    }

    void substep(Real dt);
    void findContacts(Real dt);
    void findContactsOnce(Real dt, std::span<const std::uint8_t> around, std::vector<BodyContact>& out);
    bool searchAgain(Real dt);
    void keepLastSearch();
    void rememberSearch();
    void buildIslands();
    template <class Run>
    void forEachIsland(bool ofSearch, Run run);
    void settleNewContacts();
    void searchAtPoses(Real margin);
    void rememberSettled();
    Real movePoses(Real& sinceSettled);
};

}  // namespace af
