// One step of the world; see world.h for the order of its parts and why.

#include "world_state.h"

#include "disjoint_sets.h"

#include <algorithm>
#include <numeric>
#include <tuple>

namespace af {

namespace {

// Penetration beyond the contact slop worth another projection, as a fraction of the slop (0.001
// units at Doom's 0.05): a length of its own would be 40 times looser in metres than in inches.
constexpr Real kPenetrationTolerance = 0.02;
// The start-of-step search looks this fraction of contactMargin farther than it must, so that
// its answer stands while the bodies move less than that (see World::State::findContacts).
constexpr Real kSearchSlack = 1e-4;

void join(std::vector<int>& parent, int a, int b) {
    if (a != kWorldBody && b != kWorldBody) joinSets(parent, a, b);
}

}  // namespace

void World::step() {
    State& s = *state_;
    s.report = {};
    s.counters = {};
    s.wakeDragged();
    s.startLinear.resize(s.bodies.size());
    s.startAngular.resize(s.bodies.size());
    for (std::size_t i = 0; i < s.bodies.size(); ++i) {
        s.startLinear[i] = s.bodies[i].linearVelocity;
        s.startAngular[i] = s.bodies[i].angularVelocity;
    }
    const int substeps = std::max(1, s.settings.substeps);
    const Real dt = s.settings.timeStep / substeps;
    s.rememberBeforeStep();
    for (int i = 0; i < substeps; ++i) s.substep(dt);
    s.restoreInvalidMotion();
    s.time += s.settings.timeStep;
    s.failures += s.report.failures;
    s.testRest(s.settings.timeStep);
}

// Contacts are looked for as far as each body can travel in the step (its velocity, with the
// turn of its farthest vertex), plus contactMargin, which also covers what gravity adds within
// the step (g·dt², 0.3 units at 60 Hz). This runs before the velocities are advanced, so that
// each point's bounce is judged from the velocity the bodies arrived with. Resting bodies are not looked at,
// unless an awake body touches them: then their figure wakes and the search runs again.
//
// The search looks a slack σ (kSearchSlack · contactMargin) farther. A pair it found nothing for
// was then farther apart than its margin + σ; as long as each of its bodies' surfaces has moved
// less than σ/2 since, with less than σ/2 to travel in this step (what its margin adds for it
// now), the pair is still out of reach, and the points found for pairs of such bodies, fixed to
// them, serve again (their approach velocities taken anew). Only the bodies that moved more are
// searched around again. A resting figure, whose bodies creep by rounding, keeps its contacts
// step after step; each body's contacts depend on its own motion and its partners', never on
// bodies elsewhere, so a figure steps the same whatever happens apart from it.
void World::State::findContacts(Real dt) {
    if (collision.bodyCount() == 0) return;
    searchKept = false;
    if (searchAgain(dt) && !wakeTouched()) return;
    searchKept = false;
    manifoldsOf = ManifoldsOf::Own;
    do {
        findContactsOnce(dt, bodyAwake, manifolds);
    } while (wakeTouched());
    contacts.gather(manifolds, bodies, materials);
    search.known = true;
    search.version = collision.version();
    search.poses = poses;
    search.awake = bodyAwake;
    rememberSearch();
}

void World::State::findContactsOnce(Real dt, std::span<const std::uint8_t> around, std::vector<BodyContact>& out) {
    reach.resize(bodies.size());
    moves.resize(bodies.size());
    poses.resize(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const RigidBody& b = bodies[i];
        reach[i] = dt * b.angularVelocity.norm() * radius[i];
        moves[i] = dt * b.linearVelocity;
        poses[i] = {b.position, b.rotation()};
    }
    collision.findContacts(poses, moves, reach, settings.contactMargin * (1 + kSearchSlack), around, out);
}

// The search of the last step with what the bodies that moved too far find now, in the order of a
// whole search (body pairs by their bodies, then each body against the statics); false when the
// last search cannot serve (none yet, or the collision world or the awake bodies changed).
bool World::State::searchAgain(Real dt) {
    if (!search.known || search.version != collision.version() || search.poses.size() != bodies.size() ||
        search.awake != bodyAwake)
        return false;
    const Real allowed = settings.contactMargin * kSearchSlack / 2;
    search.moving.assign(bodies.size(), 0);
    bool anyMoving = false;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        if (!bodyAwake[i]) continue;
        const RigidBody& b = bodies[i];
        const RigidPose& then = search.poses[i];
        const Real travel = dt * (b.angularVelocity.norm() * radius[i] + b.linearVelocity.norm());
        const Real moved = (b.position - then.position).norm() + (b.rotation() - then.rotation).norm() * radius[i];
        if (travel + moved <= allowed) continue;
        search.moving[i] = 1;
        anyMoving = true;
    }
    if (!anyMoving) {
        keepLastSearch();
        return true;
    }
    search.fresh.clear();
    findContactsOnce(dt, search.moving, search.fresh);
    const auto moving = [&](int body) { return body != kStaticWorld && search.moving[static_cast<std::size_t>(body)]; };
    const auto order = [](const BodyContact& c) {
        return c.bodyB == kStaticWorld ? std::tuple(1, c.bodyA, c.staticShape) : std::tuple(0, c.bodyA, c.bodyB);
    };
    manifoldsOf = ManifoldsOf::Own;
    manifolds.clear();
    contacts.clear();
    std::size_t f = 0;
    const auto addFresh = [&](std::size_t end) {
        for (; f < end; ++f) {
            manifolds.push_back(search.fresh[f]);
            contacts.add(search.fresh[f], bodies, materials);
        }
    };
    for (std::size_t k = 0; k < search.manifolds.size(); ++k) {
        const BodyContact& c = search.manifolds[k];
        if (moving(c.bodyA) || moving(c.bodyB)) continue;
        std::size_t end = f;
        while (end < search.fresh.size() && order(search.fresh[end]) < order(c)) ++end;
        addFresh(end);
        manifolds.push_back(c);
        contacts.keep(std::span(search.points).subspan(search.firstPoint[k], static_cast<std::size_t>(c.manifold.count)),
                      bodies);
    }
    addFresh(search.fresh.size());
    for (std::size_t i = 0; i < bodies.size(); ++i)
        if (search.moving[i]) search.poses[i] = poses[i];
    rememberSearch();
    return true;
}

// No body moved too far: the last search's manifolds and points, whole and in its order, with
// one keep for all points. The merge above, with nothing to merge, took them manifold by
// manifold (resting bench ragdoll: searchAgain 10.5k -> 9.1k instructions a step).
void World::State::keepLastSearch() {
    manifoldsOf = ManifoldsOf::Search;
    contacts.clear();
    contacts.keep(search.points, bodies);
    searchKept = true;
}

void World::State::rememberSearch() {
    search.manifolds = manifolds;
    search.points.assign(contacts.points().begin(), contacts.points().end());
    search.firstPoint.clear();
    std::size_t first = 0;
    for (const BodyContact& c : manifolds) {
        search.firstPoint.push_back(first);
        first += static_cast<std::size_t>(c.manifold.count);
    }
}

// Moves poses to the bodies' current poses; returns how far an awake body's surface moved at
// most from where it was: its centre's move plus what the change of rotation does to its farthest
// vertex (at most |R₁ − R₀|_F · radius). sinceSettled: the same from the poses of the last settle.
Real World::State::movePoses(Real& sinceSettled) {
    const auto distance = [&](const RigidPose& now, const RigidPose& then, std::size_t i) {
        return (now.position - then.position).norm() + (now.rotation - then.rotation).norm() * radius[i];
    };
    const bool settledKnown = settled.known && settled.poses.size() == bodies.size();
    Real moved = 0;
    sinceSettled = settledKnown ? 0 : kInfinity;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const RigidPose now{bodies[i].position, bodies[i].rotation()};
        if (bodyAwake[i]) {
            moved = std::max(moved, distance(now, poses[i], i));
            if (settledKnown) sinceSettled = std::max(sinceSettled, distance(now, settled.poses[i], i));
        }
        poses[i] = now;
    }
    return moved;
}

// Awake bodies joined by joints, contacts or rows of the extra source form an island; the world
// (kWorldBody) joins nothing. Islands are numbered in the order of their first body.
void World::State::buildIslands() {
    const std::size_t n = bodies.size();
    parent.resize(n);
    std::iota(parent.begin(), parent.end(), 0);
    auto allAwake = [&](int a, int b) { return awake(a) && awake(b); };
    for (const Joint& j : joints)
        if (allAwake(j.bodyA, j.bodyB)) join(parent, j.bodyA, j.bodyB);
    const std::span<const ContactPoint> points = contacts.points();
    for (const ContactPoint& p : points)
        if (allAwake(p.bodyA, p.bodyB)) join(parent, p.bodyA, p.bodyB);
    if (extraRows) {
        extraScratch.clear();
        extraRows(bodies, extraScratch);
        for (std::size_t r = 0; r < extraScratch.size(); ++r)
            if (allAwake(extraScratch[r].bodyA, extraScratch[r].bodyB))
                join(parent, extraScratch[r].bodyA, extraScratch[r].bodyB);
    }

    islandOfRoot.assign(n, -1);
    localOf.assign(n, kOutsideIsland);
    islandCount = 0;
    for (IslandMembers& m : members) {
        m.bodies.clear();
        m.joints.clear();
        m.points.clear();
    }
    auto islandOf = [&](int body) -> IslandMembers& {
        int& island = islandOfRoot[static_cast<std::size_t>(findRoot(parent, body))];
        if (island < 0) {
            island = static_cast<int>(islandCount++);
            if (members.size() < islandCount) members.emplace_back();
        }
        return members[static_cast<std::size_t>(island)];
    };
    for (std::size_t i = 0; i < n; ++i) {
        if (!bodyAwake[i]) continue;
        IslandMembers& m = islandOf(static_cast<int>(i));
        localOf[i] = static_cast<int>(m.bodies.size());
        m.bodies.push_back(static_cast<int>(i));
    }
    for (std::size_t k = 0; k < joints.size(); ++k)
        if (allAwake(joints[k].bodyA, joints[k].bodyB)) islandOf(joints[k].bodyA).joints.push_back(static_cast<int>(k));
    for (std::size_t k = 0; k < points.size(); ++k) {
        const ContactPoint& p = points[k];
        if (allAwake(p.bodyA, p.bodyB)) islandOf(p.bodyA != kWorldBody ? p.bodyA : p.bodyB).points.push_back(static_cast<int>(k));
    }
    if (islands.size() < islandCount) islands.resize(islandCount);
}

// Builds the islands of the current contact points, gathers each one and hands it to `run`,
// which returns whether the island changed (and is written back). ofSearch: the points are the
// search's (a step's start); islands built of the same search before are the same, unless the
// extra source, which may change its rows, joins bodies too.
//
// Islands share nothing they write: each gathers its bodies, steps them with its own solvers and
// writes them back to its own places, and reports into its own counters, which are merged in
// island order. So the islands run on the worker threads (in any order, on any thread) to the
// same bits as one after another, except with extra rows, which read the whole world's bodies.
// Islands stepped one after another get the pool for their own work (a pile's figure blocks).
template <class Run>
void World::State::forEachIsland(bool ofSearch, Run run) {
    if (!(ofSearch && searchKept && islandsOfSearch && !extraRows)) buildIslands();
    islandsOfSearch = ofSearch;
    islandReports.assign(islandCount, StepReport{});
    islandCounters.assign(islandCount, SolverCounters{});
    islandSpringWork.assign(islandCount, 0);
    const IslandWorld world{bodies, joints, contacts.points(), localOf};
    const bool shareIslands = pool && islandCount > 1 && !extraRows;
    const auto stepIsland = [&](std::size_t k) {
        IslandContext own{settings, tuning, extraRows, bodies, islandReports[k], islandCounters[k], warmStart,
                          islandSpringWork[k], shareIslands ? nullptr : pool.get()};
        Island& island = islands[k];
        island.gather(members[k].bodies, members[k].joints, members[k].points, world);
        if (run(island, own)) island.scatter(bodies, joints);
    };
    if (shareIslands) {
        warmStart.sort();  // the index the islands' recalls would otherwise build, each on its own
        pool->run(islandCount, stepIsland);
    } else {
        for (std::size_t k = 0; k < islandCount; ++k) stepIsland(k);
    }
    for (std::size_t k = 0; k < islandCount; ++k) {
        report.rows += islandReports[k].rows;
        report.residual = std::max(report.residual, islandReports[k].residual);
        report.failures += islandReports[k].failures;
        counters.add(islandCounters[k]);
        if (islandSpringWork[k] > 0)
            before.projectedSpringWork[static_cast<std::size_t>(guardGroupOf(members[k].bodies.front()))] += islandSpringWork[k];
    }
}

void World::State::startThreads() {
    if (settings.threads <= 1) {
        pool.reset();
    } else if (!pool || pool->threads() != settings.threads) {
        pool = std::make_unique<WorkerPool>(settings.threads);
    }
}

void World::State::substep(Real dt) {
    // The report tells of the last substep's velocity solves (summed over the islands).
    report.rows = 0;
    report.residual = 0;
    counters.pivots = counters.iterations = counters.largeIslands = counters.projectionPasses = 0;
    for (const Joint& j : joints)
        if (j.type == ConstraintType::Spring && (awake(j.bodyA) || awake(j.bodyB))) applySpringForces(j, bodies, dt);
    findContacts(dt);
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        if (!bodyAwake[i]) continue;
        RigidBody& b = bodies[i];
        integrateVelocity(b, settings.gravity, dt, settings.integration);
        b.force.setZero();
        b.torque.setZero();
    }
    forEachIsland(true, [&](Island& island, IslandContext& shared) {
        island.step(dt, shared);
        return true;
    });
    joinTouchingForGuard();
    warmStart.clear();
    for (std::size_t k = 0; k < islandCount; ++k) warmStart.add(islands[k].velocityWarmStart());
    settleNewContacts();
    joinTouchingForGuard();
}

// The contacts the step started with do not see everything the step did: a vertex left out of a
// four-point manifold, or turned into the floor by the step's rotation. The contacts are looked
// for again at the final poses (no margin: only what touches), and the islands where something
// penetrates deeper than the slop allows are projected once more with them. They also make
// maxPenetration() report the poses the step ends with.
//
// A pair the start search found nothing for was farther apart than its margin (at least
// contactMargin). When no body moved by more than a quarter of that in the step, such a pair is
// still apart, and only the pairs found at the start need looking at again: the same answer as a
// whole search, without the broadphase and the pairs that stayed apart (a resting figure).
void World::State::settleNewContacts() {
    if (collision.bodyCount() == 0) return;
    Real sinceSettled = 0;
    const Real moved = movePoses(sinceSettled);
    const Real allowed = settings.contact.slop * (1 + kPenetrationTolerance);
    const bool stayedApart = moved < settings.contactMargin / 4 && settings.contactMargin > 0;
    if (stayedApart && searchKept && sinceSettled <= settings.contactMargin * kSearchSlack / 2) {
        // The pairs are those the last settle looked at, and no body has moved more than σ/2
        // since: its points, body-fixed, stand as the search's do (see findContacts). Only
        // positions read them (the projection below, maxPenetration): the next step's search
        // takes their approach velocities anew before its velocity solve (resting bench ragdoll:
        // 1.4k of a step's 212k instructions to take them here).
        manifoldsOf = ManifoldsOf::Settled;
        contacts.clear();
        contacts.keepForPositions(settled.points);
        // A point's depth −n·(pA − pB) changes by at most its two bodies' surface moves, each
        // at most sinceSettled: below the tolerance by that much, no island needs a look (resting
        // bench ragdoll: settleNewContacts 4.7k -> 3.6k instructions a step).
        if (settled.penetration + 2 * sinceSettled < allowed || af::maxPenetration(contacts.points(), bodies) <= allowed)
            return;
    } else {
        if (stayedApart) {
            if (manifoldsOf != ManifoldsOf::Settled) settled.manifolds = found();
            collision.findContactsAgain(poses, 0, settled.manifolds);
        } else {
            searchAtPoses(0);
        }
        rememberSettled();
        if (settled.penetration <= allowed) return;
    }
    // The projection moves bodies by about the depth it removes, more at the end of a lever: a
    // pair apart at the poses but within twice that depth joins its problem, as a contact point
    // apart (its row keeps the gap from closing), or the projection could push a body into a
    // surface the search at margin 0 did not see (bench grid4: a forearm pushed 4.1 mm into the
    // floor by the projection of another contact 19 mm deep). Only steps that project pay for it.
    searchAtPoses(2 * af::maxPenetration(contacts.points(), bodies));
    rememberSettled();
    forEachIsland(false, [&](Island& island, IslandContext& shared) {
        if (island.maxPenetration() <= allowed) return false;
        island.project(shared);
        return true;
    });
}

// A whole search at the poses for the settle, the bodies taken as still, `margin` apart.
void World::State::searchAtPoses(Real margin) {
    std::fill(reach.begin(), reach.end(), Real(0));
    std::fill(moves.begin(), moves.end(), Vec3::Zero());
    collision.findContacts(poses, moves, reach, margin, bodyAwake, settled.manifolds);
}

// The settle's manifolds become the contacts, kept with the poses they were found at.
void World::State::rememberSettled() {
    manifoldsOf = ManifoldsOf::Settled;
    contacts.gather(settled.manifolds, bodies, materials);
    settled.known = true;
    settled.poses = poses;
    settled.points.assign(contacts.points().begin(), contacts.points().end());
    settled.penetration = af::maxPenetration(contacts.points(), bodies);
}

}  // namespace af
