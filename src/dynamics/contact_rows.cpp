// Contact rows. With r_A = p − x_A and r_B = p − x_B, the relative normal velocity at the contact
// point is  Cdot = n·(v_A + ω_A×r_A) − n·(v_B + ω_B×r_B)  =  [n │ r_A×n]·u_A − [n │ r_B×n]·u_B,
// and C is the separation along n (−depth). Tangent rows have the same form with t for n.

#include "af/dynamics/contact.h"

#include <cmath>

namespace af {

namespace {

// Two unit tangents completing n to a right-handed basis.
void tangents(const Vec3& n, Vec3& t1, Vec3& t2) {
    t1 = std::abs(n.x()) < 0.57735 ? Vec3(0, n.z(), -n.y()) : Vec3(n.y(), -n.x(), 0);
    t1.normalize();
    t2 = n.cross(t1);
}

// The world inverse inertias of a contact's two bodies (unused for the world).
struct Inertias {
    const Mat3& a;
    const Mat3& b;
};

// Appends the row along d, with its softness relative to its own J M⁻¹ Jᵀ; returns its index.
int addRowAlong(const Contact& c, std::span<const RigidBody> bodies, const Inertias& inertia, const Vec3& d,
                Real relativeCfm, ConstraintRows& out) {
    ConstraintRow& row = out.append();
    row.bodyA = c.bodyA;
    row.bodyB = c.bodyB;
    Real diagonal = 0;
    if (c.bodyA != kWorldBody) {
        const RigidBody& a = bodies[static_cast<std::size_t>(c.bodyA)];
        row.linearA = d;
        row.angularA = (c.point - a.position).cross(d);
        diagonal += a.inverseMass * row.linearA.squaredNorm() + row.angularA.dot(inertia.a * row.angularA);
    }
    if (c.bodyB != kWorldBody) {
        const RigidBody& b = bodies[static_cast<std::size_t>(c.bodyB)];
        row.linearB = -d;
        row.angularB = -(c.point - b.position).cross(d);
        diagonal += b.inverseMass * row.linearB.squaredNorm() + row.angularB.dot(inertia.b * row.angularB);
    }
    row.cfm = relativeCfm * diagonal;
    return static_cast<int>(out.size()) - 1;
}

Real velocityAlong(const Contact& c, std::span<const RigidBody> bodies, const Vec3& d) {
    Real v = 0;
    if (c.bodyA != kWorldBody) v += d.dot(bodies[static_cast<std::size_t>(c.bodyA)].velocityAt(c.point));
    if (c.bodyB != kWorldBody) v -= d.dot(bodies[static_cast<std::size_t>(c.bodyB)].velocityAt(c.point));
    return v;
}

int writeRows(const Contact& c, std::span<const RigidBody> bodies, const Inertias& inertia,
              const ContactSettings& settings, ConstraintRows& out) {
    const int normalIndex = addRowAlong(c, bodies, inertia, c.normal, settings.relativeCfm, out);
    {  // the reference holds only until the next row is appended
        ConstraintRow& normal = out[static_cast<std::size_t>(normalIndex)];
        normal.lo = 0;
        normal.hi = kInfinity;
        normal.error = settings.slop - c.depth;
        const Real approach = c.approachVelocity ? *c.approachVelocity : velocityAlong(c, bodies, c.normal);
        if (approach < -settings.restitutionThreshold) normal.target = -c.restitution * approach;
    }

    if (c.friction <= 0) return normalIndex;
    auto addFriction = [&](const Vec3& t) {
        const int index = addRowAlong(c, bodies, inertia, t, settings.relativeCfm, out);
        ConstraintRow& row = out[static_cast<std::size_t>(index)];
        row.frictionSource = normalIndex;
        row.frictionCoefficient = c.friction;
    };
    if (c.frictionDirection) {
        const Vec3 along = *c.frictionDirection - c.normal * c.normal.dot(*c.frictionDirection);
        if (along.norm() > 1e-9) {
            addFriction(along.normalized());
            return normalIndex;
        }
    }
    Vec3 t1, t2;
    tangents(c.normal, t1, t2);
    addFriction(t1);
    addFriction(t2);
    return normalIndex;
}

Mat3 inverseInertiaOf(int body, std::span<const RigidBody> bodies) {
    return body == kWorldBody ? Mat3::Zero() : bodies[static_cast<std::size_t>(body)].inverseInertiaWorld();
}

const Mat3& inverseInertiaOf(int body, std::span<const Mat3> inverseInertiaWorld) {
    static const Mat3 world = Mat3::Zero();
    return body == kWorldBody ? world : inverseInertiaWorld[static_cast<std::size_t>(body)];
}

}  // namespace

int writeContactRows(const Contact& c, std::span<const RigidBody> bodies, const ContactSettings& settings,
                     ConstraintRows& out) {
    const Mat3 a = inverseInertiaOf(c.bodyA, bodies);
    const Mat3 b = inverseInertiaOf(c.bodyB, bodies);
    return writeRows(c, bodies, {a, b}, settings, out);
}

int writeContactRows(const Contact& c, std::span<const RigidBody> bodies, std::span<const Mat3> inverseInertiaWorld,
                     const ContactSettings& settings, ConstraintRows& out) {
    return writeRows(c, bodies, {inverseInertiaOf(c.bodyA, inverseInertiaWorld), inverseInertiaOf(c.bodyB, inverseInertiaWorld)},
                     settings, out);
}

}  // namespace af
