#include "world_state.h"

#include <algorithm>

namespace af {

World::World(const WorldSettings& settings) : state_(std::make_unique<State>()) {
    State& s = *state_;
    s.settings = settings;
    s.collision = CollisionWorld(settings.collision);
}

World::World(const Figure& figure, const WorldSettings& settings) : World(settings) { addFigure(figure); }

World::World(std::vector<RigidBody> bodies, std::vector<Joint> joints, const WorldSettings& settings)
    : World(settings) {
    for (const RigidBody& b : bodies) state_->addBody(b, Polytope{}, CollisionFilter{}, BodyMaterial{}, -1);
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

int World::addFigure(const Figure& figure) {
    State& s = *state_;
    const int number = static_cast<int>(s.figures.size());
    FigureRange range;
    range.firstBody = static_cast<int>(s.bodies.size());
    range.bodyCount = static_cast<int>(figure.bodies.size());
    range.firstJoint = static_cast<int>(s.joints.size());

    std::vector<bool> heldByWorld(figure.bodies.size(), false);
    for (const FigureConstraint& c : figure.constraints)
        if (c.type != ConstraintType::Spring && c.body2 == kWorld) heldByWorld[static_cast<std::size_t>(c.body1)] = true;

    for (std::size_t i = 0; i < figure.bodies.size(); ++i) {
        const FigureBody& b = figure.bodies[i];
        RigidBody body = RigidBody::dynamic(b.mass, b.inertia, b.pose.position, Quat(b.pose.rotation));
        body.linearFriction = b.linearFriction;
        body.angularFriction = b.angularFriction;
        CollisionFilter filter;
        filter.figure = number;
        filter.selfCollision = figure.settings.selfCollision && b.selfCollision;
        filter.contents = b.contents;
        filter.clipMask = b.clipMask;
        filter.collidesWithStatic = !heldByWorld[i];
        s.addBody(body, b.shape, filter, BodyMaterial{b.contactFriction, b.bounciness, b.frictionDirection}, number);
    }
    for (const FigureConstraint& c : figure.constraints)
        if (c.type != ConstraintType::Spring && c.body2 != kWorld)
            s.collision.excludePair(range.firstBody + c.body1, range.firstBody + c.body2);

    for (Joint j : makeJoints(figure)) {
        j.bodyA += range.firstBody;
        if (j.bodyB != kWorldBody) j.bodyB += range.firstBody;
        s.joints.push_back(std::move(j));
    }
    range.jointCount = static_cast<int>(s.joints.size()) - range.firstJoint;
    s.figures.push_back(range);
    s.rest.emplace_back(restSettingsFrom(figure.settings));
    s.figureResting.push_back(0);
    s.refreshAwake();
    return number;
}

void World::setContactSource(RowSource source) { state_->extraRows = std::move(source); }
std::vector<RigidBody>& World::bodies() { return state_->bodies; }
const std::vector<RigidBody>& World::bodies() const { return state_->bodies; }
const std::vector<Joint>& World::joints() const { return state_->joints; }
const std::vector<World::FigureRange>& World::figures() const { return state_->figures; }
CollisionWorld& World::collision() { return state_->collision; }
const CollisionWorld& World::collision() const { return state_->collision; }
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
