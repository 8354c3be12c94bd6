// Overlays for the af_show* cvars (console_overlays.h), measured by show_geometry.h as the
// printed blocks are. Sizes are in world units, chosen for Doom's scale (a humanoid ~70 units
// tall); colours keep each kind apart from the others and from the bodies' palette.

#include "console_overlays.h"

#include "console/console_text.h"
#include "console/show_geometry.h"

#include "af/text/strings.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace af::console {

namespace {

using render::Colour;

constexpr Colour kAnchor = {0.10f, 0.10f, 0.12f};
constexpr Colour kShaftLimit = {0.05f, 0.65f, 0.85f};  // cones and pyramids
constexpr Colour kHingeLimit = {0.95f, 0.60f, 0.05f};
constexpr Colour kTree = {0.05f, 0.45f, 0.20f};
constexpr Colour kVelocity = {0.85f, 0.08f, 0.10f};
constexpr Colour kName = {0.08f, 0.08f, 0.10f};
constexpr Colour kHighlight = {1.00f, 0.15f, 0.80f};
constexpr Colour kInertia = {0.45f, 0.20f, 0.75f};
constexpr Colour kContact = {1.00f, 0.08f, 0.08f};  // points and normals: a red no body or other mark is
constexpr Colour kImpulse = {1.00f, 0.60f, 0.00f};

constexpr Real kAxisLength = 5;   // a joint's axis, each way from the anchor
constexpr Real kLimitSize = 7;    // a limit's cone, pyramid or fan, from the anchor
constexpr Real kVelocityTime = 0.1;  // s: an arrow reaches where its body will be this much later
constexpr Real kContactNormalLength = 4;
constexpr Real kPi = std::numbers::pi_v<Real>;

// A body's principal axes of inertia, each drawn both ways from its centre of mass as far as its
// radius of gyration about it (√(I/m)): a long thin bone shows a short axis along its length and
// two long ones across, and axes of very different lengths show lopsided inertia at a glance.
void addInertiaAxes(render::Overlay& o, const RigidBody& body) {
    if (body.inverseMass <= 0) return;
    const Eigen::SelfAdjointEigenSolver<Mat3> principal(body.inertiaWorld());
    for (int k = 0; k < 3; ++k) {
        const Real gyration = std::sqrt(std::max(Real(0), principal.eigenvalues()[k]) * body.inverseMass);
        const Vec3 axis = gyration * principal.eigenvectors().col(k);
        o.lines.push_back({body.position - axis, body.position + axis, kInertia, 1.5, false});
    }
}

// Each point of the last step's contacts as a dot with its normal, a short arrow, over a wider
// line along the normal as long as the point's normal impulse (kContactImpulseLength). `active`:
// not those whose body A (always a body) belongs to a figure at rest.
void addContacts(render::Overlay& o, const World& world, bool active) {
    const std::vector<ContactImpulse> impulses = world.contactImpulses();
    std::size_t i = 0;
    for (const BodyContact& c : world.contacts()) {
        const FigureId figure = world.figureOf(c.bodyA);
        const bool shown = !active || figure.value < 0 || !world.figureAtRest(figure);
        for (int k = 0; k < c.manifold.count; ++k, ++i) {
            if (!shown) continue;
            const Vec3& p = c.manifold.points[std::size_t(k)].point;
            if (impulses[i].normal > 0)
                o.lines.push_back({p, p + kContactImpulseLength * impulses[i].normal * c.manifold.normal, kImpulse, 4.0, false});
            o.lines.push_back({p, p + kContactNormalLength * c.manifold.normal, kContact, 1.5, true});
            o.dots.push_back({p, kContact, 3});
        }
    }
}

Colour darker(const Colour& c) { return {c[0] * 0.6f, c[1] * 0.6f, c[2] * 0.6f}; }

// Two unit vectors ⟂ `axis` and to each other.
std::pair<Vec3, Vec3> basisAround(const Vec3& axis) {
    const Vec3 u = (std::abs(axis.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(axis).normalized();
    return {u, axis.cross(u)};
}

// The rim of the allowed directions and a few lines from the apex to it, and where the limited
// shaft points now.
void addShaftLimit(render::Overlay& o, const Joint& j, std::span<const RigidBody> bodies, const Vec3& apex, const Colour& colour) {
    std::vector<Vec3> rim;
    if (j.limit == LimitType::Cone) {
        const Vec3 axis = directionOn(bodies, j.bodyB, j.cone.axis);
        const auto [u, v] = basisAround(axis);
        const Real a = std::min(j.cone.halfAngle, kPi);
        for (int i = 0; i < 32; ++i) {
            const Real t = 2 * kPi * i / 32;
            rim.push_back(apex + kLimitSize * (std::cos(a) * axis + std::sin(a) * (std::cos(t) * u + std::sin(t) * v)));
        }
    } else if (j.limit == LimitType::Pyramid) {
        const Mat3 basis = (j.bodyB == kWorldBody ? Mat3::Identity() : bodies[std::size_t(j.bodyB)].rotation()) * j.pyramid.basis;
        // Past 89° the pyramid's edges would run off to infinity.
        const Real t0 = std::tan(std::min(j.pyramid.halfAngles[0], Real(1.55))), t1 = std::tan(std::min(j.pyramid.halfAngles[1], Real(1.55)));
        for (const auto& [s0, s1] : {std::pair{1, 1}, {-1, 1}, {-1, -1}, {1, -1}})
            rim.push_back(apex + kLimitSize * (s0 * t0 * basis.col(0) + s1 * t1 * basis.col(1) + basis.col(2)).normalized());
    } else {
        return;
    }
    o.polygons.push_back({rim, colour, 0.25});
    for (std::size_t i = 0; i < rim.size(); i += rim.size() / 4) o.lines.push_back({apex, rim[i], colour, 0.8, false});
    o.lines.push_back({apex, apex + kLimitSize * directionOn(bodies, j.bodyA, j.limitShaft), darker(colour), 1.8, true});
}

// The V of allowed hinge angles as a fan ⟂ the axis, and where body A's reference points now.
void addHingeLimit(render::Overlay& o, const Joint& j, std::span<const RigidBody> bodies, const Vec3& apex, const Colour& colour) {
    const Vec3 axis = directionOn(bodies, j.bodyB, j.axisB), rB = directionOn(bodies, j.bodyB, j.referenceB), tB = axis.cross(rB);
    const Real lo = j.hinge.center - std::min(j.hinge.halfWidth, kPi), hi = j.hinge.center + std::min(j.hinge.halfWidth, kPi);
    std::vector<Vec3> fan{apex};
    const int n = std::max(2, int(std::ceil((hi - lo) / (kPi / 18))));
    for (int i = 0; i <= n; ++i) {
        const Real phi = lo + (hi - lo) * i / n;
        fan.push_back(apex + kLimitSize * (std::cos(phi) * rB + std::sin(phi) * tB));
    }
    o.polygons.push_back({fan, colour, 0.35});
    o.lines.push_back({apex, apex + kLimitSize * directionOn(bodies, j.bodyA, j.referenceA), darker(colour), 1.8, true});
}

void addLimits(render::Overlay& o, const Joint& j, std::span<const RigidBody> bodies, std::optional<Colour> colour) {
    const Vec3 apex = jointAnchor(j, bodies);
    if (j.type == ConstraintType::Hinge && j.limit != LimitType::None) addHingeLimit(o, j, bodies, apex, colour.value_or(kHingeLimit));
    else if (j.type == ConstraintType::BallAndSocket || (j.type == ConstraintType::Universal && !j.cardan.enabled))
        addShaftLimit(o, j, bodies, apex, colour.value_or(kShaftLimit));
}

// The anchor as a dot and the joint's axes as short lines through it (a spring: a line between
// its two anchors).
void addConstraint(render::Overlay& o, const Joint& j, std::span<const RigidBody> bodies, const Colour& colour, double radius) {
    const Vec3 anchor = jointAnchor(j, bodies);
    switch (j.type) {
    case ConstraintType::Hinge: {
        const Vec3 axis = directionOn(bodies, j.bodyB, j.axisB);
        o.lines.push_back({anchor - kAxisLength * axis, anchor + kAxisLength * axis, colour, 1.5, false});
        break;
    }
    case ConstraintType::Universal:
        o.lines.push_back({anchor, anchor + kAxisLength * directionOn(bodies, j.bodyA, j.axisA), colour, 1.5, false});
        o.lines.push_back({anchor, anchor + kAxisLength * directionOn(bodies, j.bodyB, j.axisB), colour, 1.5, false});
        break;
    case ConstraintType::Slider: {
        const Vec3 axis = directionOn(bodies, j.bodyB, j.axisB);
        o.lines.push_back({anchor - kAxisLength * axis, anchor + kAxisLength * axis, colour, 1.5, false});
        break;
    }
    case ConstraintType::Spring: o.lines.push_back({anchor, pointOn(bodies, j.bodyB, j.anchorB), colour, 1.0, false}); break;
    default: break;
    }
    o.dots.push_back({anchor, colour, radius});
}

}  // namespace

void addShowOverlays(render::RenderScene& scene, const World& world, const ShowFlags& flags) {
    render::Overlay& o = scene.overlay;
    const std::span<const RigidBody> bodies = world.bodies();
    for (const FigureId id : world.figureIds()) {
        if (flags.active && world.figureAtRest(id)) continue;
        const Figure& figure = world.definition(id);
        const World::FigureRange range = world.range(id);
        const auto centre = [&](int b) { return bodies[std::size_t(range.firstBody + b)].position; };
        if (flags.trees)
            for (const auto& [parent, child] : treeEdges(figure)) o.lines.push_back({centre(parent), centre(child), kTree, 1.5, true});
        for (const Joint* j : figureJoints(world, id)) {
            const bool highlighted = !flags.highlightConstraint.empty() && equalsIgnoreCase(j->name, flags.highlightConstraint);
            if (flags.limits || highlighted) addLimits(o, *j, bodies, highlighted ? std::optional(kHighlight) : std::nullopt);
            if (flags.constraints || highlighted) addConstraint(o, *j, bodies, highlighted ? kHighlight : kAnchor, highlighted ? 4.0 : 2.5);
            if (flags.constraintNames || highlighted) o.labels.push_back({jointAnchor(*j, bodies), j->name, highlighted ? kHighlight : kName});
        }
        for (int b = 0; b < range.bodyCount; ++b) {
            const RigidBody& body = bodies[std::size_t(range.firstBody + b)];
            const bool highlighted = !flags.highlightBody.empty() && equalsIgnoreCase(figure.bodies[std::size_t(b)].name, flags.highlightBody);
            if (highlighted) scene.bodies[std::size_t(range.firstBody + b)].colour = kHighlight;
            // An arrow under half a unit would be only its head: a body all but still has none.
            if (flags.velocity && body.linearVelocity.norm() * kVelocityTime > 0.5)
                o.lines.push_back({body.position, body.position + kVelocityTime * body.linearVelocity, kVelocity, 2.0, true});
            if (flags.inertia) addInertiaAxes(o, body);
            // Name and mass share one label, as Doom prints them on one line.
            std::string label = flags.bodyNames || highlighted ? figure.bodies[std::size_t(b)].name : "";
            if (flags.mass) label += (label.empty() ? "" : " ") + fixed(body.mass());
            if (!label.empty()) o.labels.push_back({body.position, label, highlighted ? kHighlight : kName});
        }
        if (flags.totalMass && range.bodyCount > 0) {
            Real total = 0;
            Vec3 top = centre(0);
            for (int b = 0; b < range.bodyCount; ++b) {
                total += bodies[std::size_t(range.firstBody + b)].mass();
                if (centre(b).z() > top.z()) top = centre(b);
            }
            o.labels.push_back({top + Vec3(0, 0, 2 * kAxisLength), "total mass " + fixed(total), kName});
        }
    }
    if (flags.contacts) addContacts(o, world, flags.active);
}

}  // namespace af::console
