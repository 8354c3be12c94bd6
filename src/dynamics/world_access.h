#pragma once
// The inside of a World, for tests and benchmarks (World befriends this struct; world.h only
// declares it): the solvers' tuning and counters, extra rows, and the bodies as writable data.
// Not part of the installed API: an embedder steers a world through World's calls, which keep
// its caches, contacts and rest in step with what they change; these do not.

#include "af/dynamics/world.h"
#include "row_source.h"
#include "solver_counters.h"
#include "solver_tuning.h"

#include <vector>

namespace af::detail {

struct WorldAccess {
    // The counters of the last step, alongside World::lastStep().
    static const SolverCounters& counters(const World& world);
    // Replaces the solvers' tuning; the islands start afresh with it at the next step (their
    // warm starts of the velocity solve are kept, as across any step).
    static void setTuning(World& world, const SolverTuning& tuning);
    // Rows added to every step, on the world's bodies (hand-made contacts); empty: none.
    static void setContactSource(World& world, RowSource source);
    // The bodies, to write what World has no call for (positions, forces, torques, air
    // friction). Nothing is woken and no cache is told: set them before the first step, or
    // know what the step keeps.
    static std::vector<RigidBody>& bodies(World& world);
};

}  // namespace af::detail
