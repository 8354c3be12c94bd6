#include "soak_drop.h"

#include "af/dynamics/world.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>

namespace af::soak {

namespace {

constexpr Real kPi = Real(3.14159265358979323846);
constexpr int kMaxPile = 16;
// The step brushes of maps/default.map (maps/README.md): x 64..192, y -64..64, z 0..32 (64 from
// x = 128). A figure "inside a brush" is placed with its origin in there.
constexpr Real kStepX0 = 70, kStepX1 = 186, kStepY = 58, kStepZ0 = 2, kStepZ1 = 60;


bool finite(const World& world) {
    for (const RigidBody& b : world.bodies())
        if (!b.position.allFinite() || !b.orientation.coeffs().allFinite() || !b.linearVelocity.allFinite() ||
            !b.angularVelocity.allFinite())
            return false;
    return true;
}

// Doom's springs pull with stretch·(L − rest)² (docs/doom-physics.md), so one displaced by d
// stores stretch·|d|³/3 (compress for a compressed one).
Real springEnergy(const World& world) {
    Real energy = 0;
    const std::vector<RigidBody>& bodies = world.bodies();
    for (const Joint& joint : world.joints()) {
        if (joint.type != ConstraintType::Spring) continue;
        auto at = [&](int body, const Vec3& anchor) {
            if (body == kWorldBody) return anchor;
            const RigidBody& b = bodies[static_cast<std::size_t>(body)];
            return Vec3(b.position + b.rotation() * anchor);
        };
        const Real d = (at(joint.bodyA, joint.anchorA) - at(joint.bodyB, joint.anchorB)).norm() - joint.spring.restLength;
        energy += (d > 0 ? joint.spring.stretch : joint.spring.compress) * std::abs(d * d * d) / 3;
    }
    return energy;
}

Real groundAt(const SoakInputs& inputs, Real x, Real y) {
    return highestTopAt(inputs.brushes, x, y).value_or(0);
}

// Places figure `index` of the pile: above the ground, sunk into it, inside the step brushes, or
// inside the figure before it. Returns what it did.
std::string place(const SoakInputs& inputs, const Figure& figure, int index, const RigidPose& previous,
                  RigidPose& placement, Random& random) {
    placement.rotation = random.rotation(kPi);
    const Real mode = random.uniform(0, 1);
    if (mode < 0.2 && index > 0) {
        placement.position = previous.position + Vec3(random.uniform(-4, 4), random.uniform(-4, 4), random.uniform(-4, 4));
        return "inside the figure before it";
    }
    if (mode < 0.4) {
        placement.position = Vec3(random.uniform(kStepX0, kStepX1), random.uniform(-kStepY, kStepY),
                                  random.uniform(kStepZ0, kStepZ1));
        return format("origin inside the step brushes at (%.1f, %.1f, %.1f)", placement.position.x(),
                      placement.position.y(), placement.position.z());
    }
    const Real x = random.uniform(-200, 250), y = random.uniform(-120, 220);
    const bool sunk = mode < 0.6;
    const Real above = sunk ? -random.uniform(0, 12) : random.uniform(1, 64);
    placement.position = Vec3(x, y, 0);
    placement.position.z() = groundAt(inputs, x, y) + above - heightRange(figure, placement).lowest;
    return format(sunk ? "lowest point %.1f units into the ground at (%.1f, %.1f)" : "lowest point %.1f units above the ground at (%.1f, %.1f)",
                  std::abs(above), x, y);
}

// Every body moved up to `offset` units and turned by up to `angle` radians, each its own way:
// joints open, limits broken.
void breakPose(World& world, FigureId id, Real offset, Real angle, Random& random) {
    std::vector<RigidPose> poses = world.bodyPoses(id);
    for (RigidPose& pose : poses) {
        const Vec3 shift = random.direction() * random.uniform(0, offset);
        pose.position += shift;
        pose.rotation = random.rotation(angle) * pose.rotation;
    }
    world.setPose(id, poses);
}

// A rigid motion of the figure up to the caps, each body's speed clamped to the linear cap.
void launch(World& world, FigureId id, Real linearFraction, Real angularFraction, Random& random) {
    const IntegrationSettings& caps = world.settings().integration;
    const Vec3 v = random.direction() * (linearFraction * caps.maxLinearSpeed);
    const Vec3 w = random.direction() * (angularFraction * caps.maxAngularSpeed);
    const int bodies = world.range(id).bodyCount;
    Vec3 centre = Vec3::Zero();
    Real mass = 0;
    for (int i = 0; i < bodies; ++i) {
        centre += world.body({id, i}).mass() * world.body({id, i}).position;
        mass += world.body({id, i}).mass();
    }
    centre /= mass;
    for (int i = 0; i < bodies; ++i) {
        Vec3 linear = v + w.cross(world.body({id, i}).position - centre);
        if (linear.norm() > caps.maxLinearSpeed) linear *= caps.maxLinearSpeed / linear.norm();
        world.setVelocity({id, i}, linear, w);
    }
}

// Steps the prepared world and measures it into `result`.
void measure(World& world, const SoakInputs& inputs, DropResult& result) {
    const Vec3 gravity = world.settings().gravity;
    const Real g = gravity.norm();
    const Vec3 up = g > 0 ? Vec3(-gravity / g) : Vec3::UnitZ();
    const std::vector<RigidBody>& bodies = world.bodies();
    std::vector<Real> startHeight, lowest;
    Real totalMass = 0;
    for (const RigidBody& b : bodies) {
        startHeight.push_back(up.dot(b.position));
        totalMass += b.mass();
    }
    lowest = startHeight;
    const Real start = world.kineticEnergy() + springEnergy(world);
    const Real slack = totalMass * g * 1;
    result.startJointError = world.maxJointError();

    const Real dt = world.settings().timeStep;
    const int maxSteps = static_cast<int>(std::ceil(inputs.seconds / dt - 1e-9));
    using Clock = std::chrono::steady_clock;
    const Clock::time_point wallStart = Clock::now();
    while (result.steps < maxSteps) {
        const Clock::time_point stepStart = Clock::now();
        world.step();
        ++result.steps;
        result.restored += static_cast<int>(world.lastStep().restored.size());
        result.stuck += static_cast<int>(world.lastStep().stuck.size());
        const Clock::time_point stepEnd = Clock::now();
        result.slowestStep = std::max(result.slowestStep, std::chrono::duration<Real>(stepEnd - stepStart).count());
        if (!finite(world)) {
            result.nonFinite = true;
            result.nonFiniteTime = world.time();
            break;
        }
        Real fallen = 0;
        for (std::size_t i = 0; i < bodies.size(); ++i) {
            lowest[i] = std::min(lowest[i], up.dot(bodies[i].position));
            fallen += bodies[i].mass() * g * (startHeight[i] - lowest[i]);
        }
        const Real kinetic = world.kineticEnergy();
        result.peakKinetic = std::max(result.peakKinetic, kinetic);
        result.energyRatio = std::max(result.energyRatio, kinetic / (start + fallen + slack));
        result.peakJointError = std::max(result.peakJointError, world.maxJointError());
        result.peakPenetration = std::max(result.peakPenetration, world.maxPenetration());
        if (world.atRest()) {
            result.restTime = world.time();
            break;
        }
        if (inputs.wallBudget > 0 && std::chrono::duration<Real>(stepEnd - wallStart).count() > inputs.wallBudget) {
            result.tooSlow = true;
            break;
        }
    }
    result.simulated = world.time();
    result.endJointError = world.maxJointError();
    result.endPenetration = world.maxPenetration();
    result.solverFailures = world.solverFailures();
}

}  // namespace

DropResult runDrop(const SoakInputs& inputs, std::uint64_t seed) {
    const auto wallStart = std::chrono::steady_clock::now();
    DropResult result;
    result.seed = seed;
    Random random(seed);

    WorldSettings settings;
    settings.timeStep = std::exp(random.uniform(std::log(Real(1) / 240), std::log(Real(1) / 15)));
    result.timeStep = settings.timeStep;
    const bool sample = !inputs.samples.empty() && random.chance(0.5);
    MadeFigure made = sample ? editedSample(inputs.samples[static_cast<std::size_t>(
                                                random.between(0, static_cast<int>(inputs.samples.size()) - 1))],
                                            random)
                             : generatedChain(random);
    // Mostly single figures (40 %) and small piles; a pile of 16 about one drop in 50.
    const Real u = random.uniform(0, 1);
    const int count = std::min(kMaxPile, 1 + static_cast<int>(std::floor(kMaxPile * u * u * u)));
    result.figure = made.label + (count > 1 ? "*" + std::to_string(count) : "");
    result.details = made.notes;
    result.details.insert(result.details.begin(), format("time step 1/%.4g s", 1 / settings.timeStep));
    if (!made.figure) {
        result.rejected = made.error;
        result.details.push_back("the .af text:\n" + made.text);
        return result;
    }

    try {
        World world(settings);
        for (const Polytope& brush : inputs.brushes) world.addStaticBrush(brush);
        RigidPose previous;
        for (int i = 0; i < count; ++i) {
            RigidPose placement;
            std::string how = "figure " + std::to_string(i + 1) + ": " + place(inputs, *made.figure, i, previous, placement, random);
            previous = placement;
            const FigureId id = world.spawn(made.figure, placement);
            if (random.chance(0.35)) {
                const Real offset = random.uniform(0, 8), angle = random.uniform(0, kPi);
                breakPose(world, id, offset, angle, random);
                how += format(", pose broken (bodies moved up to %.2f units, turned up to %.0f deg)", offset, angle * 180 / kPi);
            }
            if (random.chance(0.35)) {
                const Real linear = random.uniform(0, 1), angular = random.uniform(0, 1);
                launch(world, id, linear, angular, random);
                how += format(", launched at %.2f of the speed cap, spinning at %.2f of the spin cap", linear, angular);
            }
            result.details.push_back(how);
        }
        result.bodies = static_cast<int>(world.bodies().size());
        measure(world, inputs, result);
    } catch (const std::exception& e) {
        result.threw = e.what();
    }
    result.wallSeconds = std::chrono::duration<Real>(std::chrono::steady_clock::now() - wallStart).count();
    return result;
}

}  // namespace af::soak
