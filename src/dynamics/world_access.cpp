// World's inside for tests and benchmarks (world_access.h).

#include "world_access.h"

#include "world_state.h"

#include <utility>

namespace af::detail {

const SolverCounters& WorldAccess::counters(const World& world) { return world.state_->counters; }

// An island hands its tuning to its solvers once (Island::step), so the pool is emptied and
// built anew; islandsOfSearch = false makes the next step build the islands even where it could
// keep the last ones.
void WorldAccess::setTuning(World& world, const SolverTuning& tuning) {
    World::State& s = *world.state_;
    s.tuning = tuning;
    s.islands.clear();
    s.islandsOfSearch = false;
}

void WorldAccess::setContactSource(World& world, RowSource source) {
    world.state_->userRows = std::move(source);
    world.state_->useRowSources();
}

std::vector<RigidBody>& WorldAccess::bodies(World& world) { return world.state_->bodies; }

}  // namespace af::detail
