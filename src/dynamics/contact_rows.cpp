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

ConstraintRow rowAlong(const Contact& c, std::span<const RigidBody> bodies, const Vec3& d) {
    ConstraintRow row;
    row.bodyA = c.bodyA;
    row.bodyB = c.bodyB;
    if (c.bodyA != kWorldBody) {
        row.linearA = d;
        row.angularA = (c.point - bodies[static_cast<std::size_t>(c.bodyA)].position).cross(d);
    }
    if (c.bodyB != kWorldBody) {
        row.linearB = -d;
        row.angularB = -(c.point - bodies[static_cast<std::size_t>(c.bodyB)].position).cross(d);
    }
    return row;
}

// The row's J M⁻¹ Jᵀ, which its softness is relative to.
Real diagonal(const ConstraintRow& row, std::span<const RigidBody> bodies) {
    Real d = 0;
    if (row.bodyA != kWorldBody) {
        const RigidBody& a = bodies[static_cast<std::size_t>(row.bodyA)];
        d += a.inverseMass * row.linearA.squaredNorm() + row.angularA.dot(a.inverseInertiaWorld() * row.angularA);
    }
    if (row.bodyB != kWorldBody) {
        const RigidBody& b = bodies[static_cast<std::size_t>(row.bodyB)];
        d += b.inverseMass * row.linearB.squaredNorm() + row.angularB.dot(b.inverseInertiaWorld() * row.angularB);
    }
    return d;
}

Real velocityAlong(const Contact& c, std::span<const RigidBody> bodies, const Vec3& d) {
    Real v = 0;
    if (c.bodyA != kWorldBody) v += d.dot(bodies[static_cast<std::size_t>(c.bodyA)].velocityAt(c.point));
    if (c.bodyB != kWorldBody) v -= d.dot(bodies[static_cast<std::size_t>(c.bodyB)].velocityAt(c.point));
    return v;
}

}  // namespace

int writeContactRows(const Contact& c, std::span<const RigidBody> bodies, const ContactSettings& settings,
                     ConstraintRows& out) {
    ConstraintRow normal = rowAlong(c, bodies, c.normal);
    normal.lo = 0;
    normal.hi = kInfinity;
    normal.cfm = settings.relativeCfm * diagonal(normal, bodies);
    normal.error = settings.slop - c.depth;
    const Real approach = c.approachVelocity.value_or(velocityAlong(c, bodies, c.normal));
    if (approach < -settings.restitutionThreshold) normal.target = -c.restitution * approach;
    const int normalIndex = out.add(normal);

    if (c.friction <= 0) return normalIndex;
    auto addFriction = [&](const Vec3& t) {
        ConstraintRow row = rowAlong(c, bodies, t);
        row.frictionSource = normalIndex;
        row.frictionCoefficient = c.friction;
        row.cfm = settings.relativeCfm * diagonal(row, bodies);
        out.add(row);
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

}  // namespace af
