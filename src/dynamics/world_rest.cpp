// Rest and wake of the world's figures (world.h, rest.h).

#include "world_state.h"

#include "disjoint_sets.h"

#include <algorithm>
#include <numeric>

namespace af {

namespace {

bool overSuspendThresholds(const BodyMotion& m, const RestSettings& s) {
    return !(m.linearVelocity.norm() <= s.suspendLinearVelocity && m.angularVelocity.norm() <= s.suspendAngularVelocity &&
             m.linearAcceleration.norm() <= s.suspendLinearAcceleration &&
             m.angularAcceleration.norm() <= s.suspendAngularAcceleration);
}

}  // namespace

StuckFigure World::State::stuckness(int figure) const {
    StuckFigure out{ids[static_cast<std::size_t>(figure)]};
    for (std::size_t j = 0; j < joints.size(); ++j)  // its own joints and its binds
        if (jointFigure[j] == figure) out.jointError = std::max(out.jointError, jointError(joints[j], bodies));
    for (const ContactPoint& p : contacts.points()) {
        const bool ours = bodyFigure[static_cast<std::size_t>(p.bodyA)] == figure ||
                          (p.bodyB != kStaticWorld && bodyFigure[static_cast<std::size_t>(p.bodyB)] == figure);
        if (ours) out.penetration = std::max(out.penetration, currentDepth(p, bodies));
    }
    return out;
}

// A figure ready to rest but held with a joint open or a contact deep is stuck: resting would
// freeze the error in place. It stays awake (a drag or a neighbour may free it), reported once.
bool World::State::stuck(int figure) {
    const StuckFigure s = stuckness(figure);
    const bool isStuck = s.jointError > kStuckJointError || s.penetration > kStuckPenetration;
    std::uint8_t& reported = figureStuck[static_cast<std::size_t>(figure)];
    if (isStuck && !reported) report.stuck.push_back(s);
    reported = isStuck;
    return isStuck;
}

void World::State::refreshAwake() {
    bodyAwake.resize(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i)
        bodyAwake[i] = bodyFigure[i] < 0 || !figureResting[static_cast<std::size_t>(bodyFigure[i])];
}

void World::State::wake(int figure) {
    if (!figureResting[static_cast<std::size_t>(figure)] && !rest[static_cast<std::size_t>(figure)].atRest()) return;
    figureResting[static_cast<std::size_t>(figure)] = 0;
    rest[static_cast<std::size_t>(figure)].wake();
    refreshAwake();
}

void World::State::putToRest(int figure) {
    const FigureRange& r = figures[static_cast<std::size_t>(figure)];
    for (int b = r.firstBody; b < r.firstBody + r.bodyCount; ++b) {
        RigidBody& body = bodies[static_cast<std::size_t>(b)];
        body.linearVelocity.setZero();
        body.angularVelocity.setZero();
        body.force.setZero();
        body.torque.setZero();
    }
    figureResting[static_cast<std::size_t>(figure)] = 1;
    rest[static_cast<std::size_t>(figure)].putToRest();
}

// A resting figure touched by an awake body wakes: something moved against it.
bool World::State::wakeTouched() {
    bool woke = false;
    for (const BodyContact& c : found()) {
        if (c.bodyB == kStaticWorld || awake(c.bodyA) == awake(c.bodyB)) continue;
        wake(bodyFigure[static_cast<std::size_t>(awake(c.bodyA) ? c.bodyB : c.bodyA)]);
        woke = true;
    }
    return woke;
}

// Every awake figure asks its monitor. Figures that touch form a group, which rests only as a
// whole: a figure ready to rest while a neighbour is not stays awake (and ready, as long as it
// keeps below its suspend thresholds), so a pile goes to sleep at once and no figure sleeps
// propped against one that still moves.
void World::State::testRest(Real dt) {
    if (!settings.comeToRest || figures.empty()) return;
    std::vector<std::uint8_t> ready(figures.size(), 0);
    for (std::size_t f = 0; f < figures.size(); ++f) {
        if (figureResting[f]) continue;
        const FigureRange& r = figures[f];
        motion.resize(static_cast<std::size_t>(r.bodyCount));
        bool moving = false;
        for (int i = 0; i < r.bodyCount; ++i) {
            const std::size_t b = static_cast<std::size_t>(r.firstBody + i);
            const RigidBody& body = bodies[b];
            BodyMotion& m = motion[static_cast<std::size_t>(i)];
            m.linearVelocity = body.linearVelocity;
            m.angularVelocity = body.angularVelocity;
            m.linearAcceleration = (body.linearVelocity - startLinear[b]) / dt;
            m.angularAcceleration = (body.angularVelocity - startAngular[b]) / dt;
            m.pose = {body.position, body.rotation()};
            moving = moving || overSuspendThresholds(m, rest[f].settings());
        }
        RestMonitor& monitor = rest[f];
        if (monitor.atRest() && moving) monitor.wake();
        ready[f] = monitor.update(dt, motion) && !stuck(static_cast<int>(f));
        // A held figure hangs still yet is not resting: the drag sets its velocities every step.
        if (drag && slotOfId[static_cast<std::size_t>(drag->body.figure.value)] == static_cast<int>(f)) ready[f] = 0;
    }

    group.resize(figures.size());
    std::iota(group.begin(), group.end(), 0);
    for (const BodyContact& c : found()) {
        if (c.bodyB == kStaticWorld) continue;
        const int fa = bodyFigure[static_cast<std::size_t>(c.bodyA)], fb = bodyFigure[static_cast<std::size_t>(c.bodyB)];
        if (fa >= 0 && fb >= 0) joinSets(group, fa, fb);
    }
    std::vector<std::uint8_t> groupReady(figures.size(), 1);
    for (std::size_t f = 0; f < figures.size(); ++f)
        if (!figureResting[f] && !ready[f]) groupReady[static_cast<std::size_t>(findRoot(group, static_cast<int>(f)))] = 0;
    bool changed = false;
    for (std::size_t f = 0; f < figures.size(); ++f)
        if (!figureResting[f] && groupReady[static_cast<std::size_t>(findRoot(group, static_cast<int>(f)))]) {
            putToRest(static_cast<int>(f));
            changed = true;
        }
    if (changed) refreshAwake();
}

bool World::figureAtRest(FigureId figure) const {
    return state_->figureResting[static_cast<std::size_t>(state_->slot(figure))] != 0;
}

bool World::atRest() const {
    const State& s = *state_;
    return !s.figures.empty() && std::all_of(s.figureResting.begin(), s.figureResting.end(), [](std::uint8_t r) { return r != 0; });
}

void World::wakeFigure(FigureId figure) { state_->wake(state_->slot(figure)); }

void World::putToRest(FigureId figure) {
    State& s = *state_;
    s.putToRest(s.slot(figure));
    s.refreshAwake();
}

void World::removeStatic(int staticShape) {
    State& s = *state_;
    s.collision.removeStatic(staticShape);
    for (std::size_t f = 0; f < s.figures.size(); ++f) s.wake(static_cast<int>(f));
}

}  // namespace af
