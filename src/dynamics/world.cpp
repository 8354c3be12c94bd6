// World: construction, spawning, and queries (world.h). Removing and re-posing figures, drags and
// binds are in world_figures.cpp, the step in world_step.cpp, rest in world_rest.cpp.

#include "world_state.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace af {

World::World(const WorldSettings& settings) : state_(std::make_unique<State>()) {
    checkSettings(settings, "World");
    State& s = *state_;
    s.settings = settings;
    s.collision = CollisionWorld(settings.collision);
    s.startThreads();
}

World::World(const Figure& figure, const WorldSettings& settings) : World(settings) { addFigure(figure); }

World::World(std::vector<RigidBody> bodies, std::vector<Joint> joints, const WorldSettings& settings)
    : World(settings) {
    for (const RigidBody& b : bodies) state_->addBody(b, Polytope{}, CollisionFilter{}, BodyMaterial{}, -1);
    state_->jointFigure.assign(joints.size(), -1);
    state_->jointIsBind.assign(joints.size(), 0);
    state_->joints = std::move(joints);
    state_->refreshAwake();
}

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

void World::State::addBody(const RigidBody& body, const Polytope& shape, const CollisionFilter& filter,
                           const BodyMaterial& material, int figure) {
    bodies.push_back(body);
    bodyFigure.push_back(figure);
    collision.addBody(shape, filter);
    materials.push_back(material);
    Real r = 0;
    for (const Vec3& v : shape.vertices) r = std::max(r, v.norm());
    radius.push_back(r);
}

// The figure's bodies follow every body in the world, its joints every joint (binds included).
FigureId World::State::addFigure(const Figure& figure, std::shared_ptr<const Figure> definition) {
    const int slot = static_cast<int>(figures.size());
    const FigureId id{static_cast<int>(slotOfId.size())};
    FigureRange range;
    range.firstBody = static_cast<int>(bodies.size());
    range.bodyCount = static_cast<int>(figure.bodies.size());
    range.firstJoint = static_cast<int>(joints.size());

    std::vector<bool> heldByWorld(figure.bodies.size(), false);
    for (const FigureConstraint& c : figure.constraints)
        if (c.type != ConstraintType::Spring && c.body2 == kWorld) heldByWorld[static_cast<std::size_t>(c.body1)] = true;

    for (std::size_t i = 0; i < figure.bodies.size(); ++i) {
        const FigureBody& b = figure.bodies[i];
        RigidBody body = RigidBody::dynamic(b.mass, b.inertia, b.pose.position, Quat(b.pose.rotation));
        body.linearFriction = b.linearFriction;
        body.angularFriction = b.angularFriction;
        CollisionFilter filter;
        filter.figure = id.value;  // ids, unlike slots, never change
        filter.selfCollision = figure.settings.selfCollision && b.selfCollision;
        filter.contents = b.contents;
        filter.clipMask = b.clipMask;
        filter.collidesWithStatic = !heldByWorld[i];
        addBody(body, b.shape, filter, BodyMaterial{b.contactFriction, b.bounciness, b.frictionDirection}, slot);
    }
    for (const FigureConstraint& c : figure.constraints)
        if (c.type != ConstraintType::Spring && c.body2 != kWorld)
            collision.excludePair(range.firstBody + c.body1, range.firstBody + c.body2);

    for (Joint j : makeJoints(figure)) {
        j.bodyA += range.firstBody;
        if (j.bodyB != kWorldBody) j.bodyB += range.firstBody;
        joints.push_back(std::move(j));
        jointFigure.push_back(slot);
        jointIsBind.push_back(0);
    }
    range.jointCount = static_cast<int>(joints.size()) - range.firstJoint;
    figures.push_back(range);
    definitions.push_back(std::move(definition));
    ids.push_back(id);
    slotOfId.push_back(slot);
    rest.emplace_back(restSettingsFrom(figure.settings));
    figureResting.push_back(0);
    figureStuck.push_back(0);
    refreshAwake();
    return id;
}

int World::State::slot(FigureId figure) const {
    if (figure.value < 0 || figure.value >= static_cast<int>(slotOfId.size()) ||
        slotOfId[static_cast<std::size_t>(figure.value)] < 0)
        throw std::invalid_argument("World: no figure " + std::to_string(figure.value) + " (never spawned, or removed)");
    return slotOfId[static_cast<std::size_t>(figure.value)];
}

int World::State::bodyIndex(BodyRef body) const {
    const FigureRange& r = figures[static_cast<std::size_t>(slot(body.figure))];
    if (body.body < 0 || body.body >= r.bodyCount)
        throw std::invalid_argument("World: figure " + std::to_string(body.figure.value) + " has no body " +
                                    std::to_string(body.body));
    return r.firstBody + body.body;
}

FigureId World::spawn(std::shared_ptr<const Figure> definition, const RigidPose& placement) {
    if (!definition) throw std::invalid_argument("World::spawn: no figure");
    if (!placement.position.allFinite() || !placement.rotation.allFinite())
        throw std::invalid_argument("World::spawn: the placement is not finite");
    const Figure placed = placeFigure(*definition, placement);
    return state_->addFigure(placed, std::move(definition));
}

FigureId World::addFigure(const Figure& figure) { return state_->addFigure(figure, std::make_shared<const Figure>(figure)); }

bool World::contains(FigureId figure) const {
    const State& s = *state_;
    return figure.value >= 0 && figure.value < static_cast<int>(s.slotOfId.size()) &&
           s.slotOfId[static_cast<std::size_t>(figure.value)] >= 0;
}

std::vector<FigureId> World::figureIds() const { return state_->ids; }
const Figure& World::definition(FigureId figure) const {
    return *state_->definitions[static_cast<std::size_t>(state_->slot(figure))];
}
World::FigureRange World::range(FigureId figure) const { return state_->figures[static_cast<std::size_t>(state_->slot(figure))]; }
const RigidBody& World::body(BodyRef body) const { return state_->bodies[static_cast<std::size_t>(state_->bodyIndex(body))]; }

std::vector<RigidPose> World::bodyPoses(FigureId figure) const {
    const FigureRange r = range(figure);
    std::vector<RigidPose> out;
    out.reserve(static_cast<std::size_t>(r.bodyCount));
    for (int i = r.firstBody; i < r.firstBody + r.bodyCount; ++i) {
        const RigidBody& b = state_->bodies[static_cast<std::size_t>(i)];
        out.push_back({b.position, b.rotation()});
    }
    return out;
}

Skeleton World::skeleton(FigureId figure) const { return poseSkeleton(definition(figure), bodyPoses(figure)); }

FigureId World::figureOf(int body) const {
    const int slot = state_->bodyFigure[static_cast<std::size_t>(body)];
    return slot < 0 ? FigureId{} : state_->ids[static_cast<std::size_t>(slot)];
}

const std::vector<RigidBody>& World::bodies() const { return state_->bodies; }
const std::vector<Joint>& World::joints() const { return state_->joints; }
const CollisionWorld& World::collision() const { return state_->collision; }
int World::addStaticPlane(const Plane& plane, ContentsMask contents) { return state_->collision.addPlane(plane, contents); }
int World::addStaticBrush(const Polytope& worldShape, ContentsMask contents) {
    return state_->collision.addStatic(worldShape, contents);
}
const WorldSettings& World::settings() const { return state_->settings; }
Real World::time() const { return state_->time; }
const StepReport& World::lastStep() const { return state_->report; }
int World::solverFailures() const { return state_->failures; }
const std::vector<BodyContact>& World::contacts() const { return state_->found(); }
Real World::maxPenetration() const { return af::maxPenetration(state_->contacts.points(), state_->bodies); }

Real World::maxJointError() const {
    Real worst = 0;
    for (const Joint& j : state_->joints) worst = std::max(worst, jointError(j, state_->bodies));
    return worst;
}

Real World::maxLimitViolationDegrees() const {
    Real worst = 0;
    for (const Joint& j : state_->joints) worst = std::max(worst, limitViolationDegrees(j, state_->bodies));
    return worst;
}

Real World::kineticEnergy() const {
    Real sum = 0;
    for (const RigidBody& b : state_->bodies) sum += b.kineticEnergy();
    return sum;
}

std::vector<RigidPose> World::bodyPoses() const {
    std::vector<RigidPose> out;
    for (const RigidBody& b : state_->bodies) out.push_back({b.position, b.rotation()});
    return out;
}

}  // namespace af
