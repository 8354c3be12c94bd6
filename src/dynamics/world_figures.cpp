// World: removing and re-posing figures, velocities, impulses and forces, the drag and binds
// (world.h). Removal closes the gap in the body and joint arrays, so that a step costs what the
// figures in the world cost, whatever came and went; the caches that name bodies by index are
// then dropped and the next step starts them afresh.

#include "world_state.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace af {

namespace {

// The drag rows' softness relative to their diagonal (as the joints' kJointRelativeCfm).
constexpr Real kDragRelativeCfm = 1e-6;

bool finite(const RigidPose& pose) { return pose.position.allFinite() && pose.rotation.allFinite(); }

void requireFinite(const Vec3& v, const char* what) {
    if (!v.allFinite()) throw std::invalid_argument(std::string("World: ") + what + " is not finite");
}

// The angular velocity that turns `from` into `to` in `dt`: axis · angle / dt.
Vec3 turnRate(const Mat3& from, const Mat3& to, Real dt) {
    const Eigen::AngleAxis<Real> turn(to * from.transpose());
    return turn.axis() * turn.angle() / dt;
}

}  // namespace

void World::State::wakeTouching(int slot) {
    for (const BodyContact& c : found()) {
        if (c.bodyB == kStaticWorld) continue;
        const int a = bodyFigure[static_cast<std::size_t>(c.bodyA)], b = bodyFigure[static_cast<std::size_t>(c.bodyB)];
        if (a == slot && b >= 0) wake(b);
        if (b == slot && a >= 0) wake(a);
    }
}

void World::State::removeSlot(int slot) {
    const FigureRange r = figures[static_cast<std::size_t>(slot)];
    const auto first = static_cast<std::ptrdiff_t>(r.firstBody), last = first + r.bodyCount;
    bodies.erase(bodies.begin() + first, bodies.begin() + last);
    bodyFigure.erase(bodyFigure.begin() + first, bodyFigure.begin() + last);
    materials.erase(materials.begin() + first, materials.begin() + last);
    radius.erase(radius.begin() + first, radius.begin() + last);
    collision.removeBodies(r.firstBody, r.bodyCount);
    for (int& f : bodyFigure)
        if (f > slot) --f;

    const auto moved = [&](int body) { return body >= r.firstBody + r.bodyCount ? body - r.bodyCount : body; };
    std::size_t kept = 0;
    for (std::size_t k = 0; k < joints.size(); ++k) {
        if (jointFigure[k] == slot) continue;
        Joint j = std::move(joints[k]);
        j.bodyA = moved(j.bodyA);
        if (j.bodyB != kWorldBody) j.bodyB = moved(j.bodyB);
        joints[kept] = std::move(j);
        jointFigure[kept] = jointFigure[k] > slot ? jointFigure[k] - 1 : jointFigure[k];
        jointIsBind[kept] = jointIsBind[k];
        ++kept;
    }
    joints.resize(kept);
    jointFigure.resize(kept);
    jointIsBind.resize(kept);

    const auto at = static_cast<std::ptrdiff_t>(slot);
    slotOfId[static_cast<std::size_t>(ids[static_cast<std::size_t>(slot)].value)] = -1;
    for (std::size_t k = static_cast<std::size_t>(slot) + 1; k < ids.size(); ++k) --slotOfId[static_cast<std::size_t>(ids[k].value)];
    figures.erase(figures.begin() + at);
    definitions.erase(definitions.begin() + at);
    ids.erase(ids.begin() + at);
    rest.erase(rest.begin() + at);
    figureResting.erase(figureResting.begin() + at);
    figureStuck.erase(figureStuck.begin() + at);
    renumber();
}

void World::State::renumber() {
    for (FigureRange& r : figures) r = FigureRange{};
    for (std::size_t i = bodies.size(); i-- > 0;) {
        if (bodyFigure[i] < 0) continue;
        FigureRange& r = figures[static_cast<std::size_t>(bodyFigure[i])];
        r.firstBody = static_cast<int>(i);
        ++r.bodyCount;
    }
    for (std::size_t k = joints.size(); k-- > 0;) {
        if (jointFigure[k] < 0 || jointIsBind[k]) continue;
        FigureRange& r = figures[static_cast<std::size_t>(jointFigure[k])];
        r.firstJoint = static_cast<int>(k);
        ++r.jointCount;
    }
    search = ContactSearch{};
    settled = SettledContacts{};
    searchKept = islandsOfSearch = false;
    manifolds.clear();
    manifoldsOf = ManifoldsOf::Own;
    contacts.clear();
    warmStart.clear();
    islands.clear();
    members.clear();
    islandCount = 0;
    group.clear();
    refreshAwake();
}

void World::remove(FigureId figure) {
    State& s = *state_;
    const int slot = s.slot(figure);
    s.wakeTouching(slot);
    if (s.drag && s.drag->body.figure == figure) clearDrag();
    s.removeSlot(slot);
}

FigureId World::spawnFromPose(std::shared_ptr<const Figure> definition, const Skeleton& pose, const Skeleton* earlierPose,
                              Real dt) {
    if (!definition) throw std::invalid_argument("World::spawnFromPose: no figure");
    const Figure& f = *definition;
    const auto bodyPosesOf = [&](const Skeleton& skeleton) {
        if (skeleton.size() != f.afPose.size())
            throw std::invalid_argument("World::spawnFromPose: the pose has " + std::to_string(skeleton.size()) +
                                        " joints, the figure's skeleton " + std::to_string(f.afPose.size()));
        std::vector<RigidPose> out;
        for (const FigureBody& b : f.bodies) {
            if (b.joint < 0) throw std::invalid_argument("World::spawnFromPose: body " + b.name + " drives no joint");
            const JointTransform& j = skeleton.joints[static_cast<std::size_t>(b.joint)];
            out.push_back(RigidPose{j.position, j.rotation} * b.bodyInJoint);
        }
        return out;
    };
    const std::vector<RigidPose> now = bodyPosesOf(pose);
    std::vector<RigidPose> before;
    if (earlierPose) {
        if (!(dt > 0) || !std::isfinite(dt)) throw std::invalid_argument("World::spawnFromPose: dt must be positive");
        before = bodyPosesOf(*earlierPose);
    }
    for (const RigidPose& p : now)
        if (!finite(p)) throw std::invalid_argument("World::spawnFromPose: the pose is not finite");
    const FigureId id = spawn(std::move(definition));
    setPose(id, now);
    for (std::size_t b = 0; b < before.size(); ++b)
        setVelocity({id, static_cast<int>(b)}, (now[b].position - before[b].position) / dt,
                    turnRate(before[b].rotation, now[b].rotation, dt));
    return id;
}

void World::setPose(FigureId figure, std::span<const RigidPose> poses) {
    State& s = *state_;
    const int slot = s.slot(figure);
    const FigureRange r = s.figures[static_cast<std::size_t>(slot)];
    if (poses.size() != static_cast<std::size_t>(r.bodyCount))
        throw std::invalid_argument("World::setPose: " + std::to_string(poses.size()) + " poses for " +
                                    std::to_string(r.bodyCount) + " bodies");
    for (const RigidPose& p : poses)
        if (!finite(p)) throw std::invalid_argument("World::setPose: a pose is not finite");
    s.wakeTouching(slot);
    for (std::size_t i = 0; i < poses.size(); ++i) {
        RigidBody& b = s.bodies[static_cast<std::size_t>(r.firstBody) + i];
        b.position = poses[i].position;
        b.orientation = Quat(poses[i].rotation).normalized();
        b.linearVelocity.setZero();
        b.angularVelocity.setZero();
        b.force.setZero();
        b.torque.setZero();
    }
    s.search.known = false;
    s.settled.known = false;
    s.wake(slot);
}

void World::setVelocity(BodyRef body, const Vec3& linear, const Vec3& angular) {
    setVelocity(state_->bodyIndex(body), linear, angular);
}

void World::setVelocity(int body, const Vec3& linear, const Vec3& angular) {
    requireFinite(linear, "a linear velocity");
    requireFinite(angular, "an angular velocity");
    State& s = *state_;
    if (const int f = s.bodyFigure[static_cast<std::size_t>(body)]; f >= 0) s.wake(f);
    RigidBody& b = s.bodies[static_cast<std::size_t>(body)];
    b.linearVelocity = linear;
    b.angularVelocity = angular;
}

void World::applyImpulse(BodyRef body, const Vec3& worldPoint, const Vec3& impulse) {
    applyImpulse(state_->bodyIndex(body), worldPoint, impulse);
}

void World::addForce(BodyRef body, const Vec3& worldPoint, const Vec3& force) {
    addForce(state_->bodyIndex(body), worldPoint, force);
}

void World::applyImpulse(int body, const Vec3& worldPoint, const Vec3& impulse) {
    requireFinite(worldPoint, "an impulse's point");
    requireFinite(impulse, "an impulse");
    State& s = *state_;
    if (!(impulse.norm() >= s.settings.impulseThreshold)) return;
    if (const int f = s.bodyFigure[static_cast<std::size_t>(body)]; f >= 0) s.wake(f);
    RigidBody& b = s.bodies[static_cast<std::size_t>(body)];
    b.linearVelocity += b.inverseMass * impulse;
    b.angularVelocity += b.inverseInertiaWorld() * (worldPoint - b.position).cross(impulse);
}

void World::addForce(int body, const Vec3& worldPoint, const Vec3& force) {
    requireFinite(worldPoint, "a force's point");
    requireFinite(force, "a force");
    State& s = *state_;
    if (const int f = s.bodyFigure[static_cast<std::size_t>(body)]; f >= 0) s.wake(f);
    RigidBody& b = s.bodies[static_cast<std::size_t>(body)];
    b.force += force;
    b.torque += (worldPoint - b.position).cross(force);
}

void World::setDrag(const Drag& drag) {
    State& s = *state_;
    s.bodyIndex(drag.body);
    requireFinite(drag.localPoint, "the drag's point");
    requireFinite(drag.target, "the drag's target");
    if (!(drag.damping >= 0 && drag.damping < 1)) throw std::invalid_argument("World::setDrag: damping must be in [0, 1)");
    s.drag = drag;
    s.useRowSources();
    s.wake(s.slot(drag.body.figure));
}

void World::clearDrag() {
    state_->drag.reset();
    state_->useRowSources();
}
const std::optional<Drag>& World::drag() const { return state_->drag; }

// docs/doom-physics.md §5.2, as rows. Doom sets the grabbed body's velocities and lets the solve
// follow; a hand carrying a whole figure then loses most of that velocity to the figure's weight
// and hangs far below the cursor (our humanoid's hand 18 units below, held for 2 s). Here the
// law is the wanted velocity of the grabbed point, damping · its velocity + (1 − damping) · the
// velocity that closes the gap in one step, written as three rows solved with the figure, so the
// point gets it whatever it carries. In the position projection the rows hold the point still.
void World::State::writeDragRows(std::span<const RigidBody> all, ConstraintRows& rows) const {
    const int index = bodyIndex(drag->body);
    const RigidBody& b = all[static_cast<std::size_t>(index)];
    const Vec3 arm = b.rotation() * drag->localPoint;
    const Vec3 point = b.position + arm;
    const Vec3 wanted = drag->damping * b.velocityAt(point) + (1 - drag->damping) * (drag->target - point) / settings.timeStep;
    const Mat3 inverseInertia = b.inverseInertiaWorld();
    for (int k = 0; k < 3; ++k) {
        const Vec3 e = Vec3::Unit(k);
        ConstraintRow row;
        row.bodyA = index;
        row.linearA = e;
        row.angularA = arm.cross(e);
        row.target = wanted[k];
        // Soft enough to give way to the figure's joints when a bind or the world holds it.
        row.cfm = kDragRelativeCfm * (b.inverseMass + row.angularA.dot(inverseInertia * row.angularA));
        rows.add(row);
    }
}

void World::State::useRowSources() {
    if (!drag) {
        extraRows = userRows;
        return;
    }
    extraRows = [this](std::span<const RigidBody> all, ConstraintRows& rows) {
        if (userRows) userRows(all, rows);
        writeDragRows(all, rows);
    };
}

void World::State::wakeDragged() {
    if (drag) wake(slot(drag->body.figure));
}

void World::bind(BodyRef body, const Vec3& worldAnchor) {
    requireFinite(worldAnchor, "a bind's anchor");
    State& s = *state_;
    const int index = s.bodyIndex(body);
    const RigidBody& b = s.bodies[static_cast<std::size_t>(index)];
    Joint j;
    j.type = ConstraintType::BallAndSocket;
    j.name = "bind";
    j.bodyA = index;
    j.bodyB = kWorldBody;
    j.anchorA = b.rotation().transpose() * (worldAnchor - b.position);
    j.anchorB = worldAnchor;
    s.joints.push_back(std::move(j));
    s.jointFigure.push_back(s.slot(body.figure));
    s.jointIsBind.push_back(1);
    s.wake(s.slot(body.figure));
}

void World::unbind(FigureId figure) {
    State& s = *state_;
    const int slot = s.slot(figure);
    std::size_t kept = 0;
    for (std::size_t k = 0; k < s.joints.size(); ++k) {
        if (s.jointIsBind[k] && s.jointFigure[k] == slot) continue;
        s.joints[kept] = std::move(s.joints[k]);
        s.jointFigure[kept] = s.jointFigure[k];
        s.jointIsBind[kept] = s.jointIsBind[k];
        ++kept;
    }
    if (kept == s.joints.size()) return;
    s.joints.resize(kept);
    s.jointFigure.resize(kept);
    s.jointIsBind.resize(kept);
    s.renumber();
    s.wake(slot);
}

int World::bindCount(FigureId figure) const {
    const State& s = *state_;
    const int slot = s.slot(figure);
    int n = 0;
    for (std::size_t k = 0; k < s.joints.size(); ++k) n += s.jointIsBind[k] && s.jointFigure[k] == slot;
    return n;
}

}  // namespace af
