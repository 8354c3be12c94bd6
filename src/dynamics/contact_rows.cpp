// Contact rows, of a hand-made Contact (contact_rows.h) and of the step's ContactPoints (contact_set.h),
// by the same arithmetic. A contact pushes A at p_A and B at p_B: a hand-made Contact's one point
// is both, a ContactPoint's are its two surface points, which part when the bodies slide or turn
// on each other after the points were found (by up to a quarter of the contact margin before
// they are found again). With r_A = p_A − x_A and r_B = p_B − x_B, the relative normal velocity
//     Cdot = n·(v_A + ω_A×r_A) − n·(v_B + ω_B×r_B)  =  [n │ r_A×n]·u_A − [n │ r_B×n]·u_B
// is exactly the rate of the separation C = n·(p_A − p_B) (−depth) for the step's fixed n, so
// the position projection's Newton passes converge quadratically on contacts too. With the
// midpoint of p_A and p_B as both levers they converged linearly where a body had slid, and on
// the bench ragdoll: 239 projection passes against 193, 857M instructions against 682M, at rest
// from step 99 either way; sixteen ragdolls (grid4) at rest from step 142 against 283. The price:
// between two bodies whose points have parted by s, a contact's equal and opposite impulses
// exert a torque s × λ on the pair, as Bullet's, which pushes each body at its own point too.
// Tangent rows have the same form with t for n.

#include "contact_set.h"

#include <cmath>

namespace af {

namespace {

// A contact as the writer reads it: a Contact's optional parts as pointers (null when absent),
// so that each caller builds it on the stack without copying optionals.
struct ContactView {
    int bodyA = kWorldBody;
    int bodyB = kWorldBody;
    Vec3 pointA;                              // world: where the rows push A
    Vec3 pointB;                              // world: where they push B
    Vec3 normal;                              // world, unit, B towards A
    Real depth = 0;
    Real friction = 0;
    Real restitution = 0;
    const Real* approachVelocity = nullptr;   // empty: the bodies' current velocities
    const Vec3* frictionDirection = nullptr;  // world
    const Vec3* tangents = nullptr;           // null, or tangents(normal) already at hand (two)
};

// Two unit tangents completing n to a right-handed basis.
void tangents(const Vec3& n, Vec3& t1, Vec3& t2) {
    t1 = std::abs(n.x()) < 0.57735 ? Vec3(0, n.z(), -n.y()) : Vec3(n.y(), -n.x(), 0);
    t1.normalize();
    t2 = n.cross(t1);
}

// One body of a contact, looked up once for all of its rows; body is null for the world.
struct ContactSide {
    const RigidBody* body = nullptr;
    const Mat3* inverseInertia = nullptr;
    Vec3 lever = Vec3::Zero();  // r = p − x
};

ContactSide sideOf(int index, std::span<const RigidBody> bodies, const Mat3& inverseInertia, const Vec3& point) {
    if (index == kWorldBody) return {};
    const RigidBody& body = bodies[static_cast<std::size_t>(index)];
    return {&body, &inverseInertia, point - body.position};
}

// A contact row's members besides its Jacobian and softness.
struct RowRest {
    Real target = 0;
    Real error = 0;
    Real lo = -kInfinity;
    Real hi = kInfinity;
    int frictionSource = -1;
    Real frictionCoefficient = 0;
};

// Appends the row along d, with its softness relative to its own J M⁻¹ Jᵀ, made in place with
// each member written once. Inlined into writeRows, so that the three rows of a point share the
// loads of its bodies, lever arms and inertias (and no call costs a frame).
[[gnu::always_inline]] inline void addRowAlong(const ContactView& c, const ContactSide& a, const ContactSide& b, const Vec3& d,
                                               Real relativeCfm, const RowRest& rest, ConstraintRows& out) {
    Vec3 linearA = Vec3::Zero(), angularA = Vec3::Zero(), linearB = Vec3::Zero(), angularB = Vec3::Zero();
    Real diagonal = 0;
    if (a.body) {
        linearA = d;
        angularA = a.lever.cross(d);
        diagonal += a.body->inverseMass * linearA.squaredNorm() + angularA.dot(*a.inverseInertia * angularA);
    }
    if (b.body) {
        linearB = -d;
        angularB = -b.lever.cross(d);
        diagonal += b.body->inverseMass * linearB.squaredNorm() + angularB.dot(*b.inverseInertia * angularB);
    }
    out.appendMade(c.bodyA, c.bodyB, linearA, angularA, linearB, angularB, rest.target, rest.error, rest.lo, rest.hi,
                   rest.frictionSource, rest.frictionCoefficient, relativeCfm * diagonal);
}

Real velocityAlong(const ContactView& c, const ContactSide& a, const ContactSide& b, const Vec3& d) {
    Real v = 0;
    if (a.body) v += d.dot(a.body->velocityAt(c.pointA));
    if (b.body) v -= d.dot(b.body->velocityAt(c.pointB));
    return v;
}

// Appends the contact's rows; returns the index of its normal row. inverseInertiaA/B: the world
// inverse inertias of A and B (not read for the world). Inlined into each of its callers.
[[gnu::always_inline]] inline int writeRows(const ContactView& c, std::span<const RigidBody> bodies, const Mat3& inverseInertiaA,
              const Mat3& inverseInertiaB, const ContactSettings& settings, ConstraintRows& out) {
    const ContactSide a = sideOf(c.bodyA, bodies, inverseInertiaA, c.pointA);
    const ContactSide b = sideOf(c.bodyB, bodies, inverseInertiaB, c.pointB);
    const int normalIndex = static_cast<int>(out.size());
    {
        RowRest normal{.error = settings.slop - c.depth, .lo = 0};
        const Real approach = c.approachVelocity ? *c.approachVelocity : velocityAlong(c, a, b, c.normal);
        if (approach < -settings.restitutionThreshold) normal.target = -c.restitution * approach;
        addRowAlong(c, a, b, c.normal, settings.relativeCfm, normal, out);
    }

    if (c.friction <= 0 || !settings.friction) return normalIndex;
    // One loop over the directions, not a call per row: the row writer is inlined once.
    Vec3 directions[2];
    int count = 2;
    if (c.tangents && !c.frictionDirection) {
        directions[0] = c.tangents[0];
        directions[1] = c.tangents[1];
    } else {
        count = frictionDirections(c.normal, c.frictionDirection, directions);
    }
    const RowRest friction{.frictionSource = normalIndex, .frictionCoefficient = c.friction};
    for (int k = 0; k < count; ++k) addRowAlong(c, a, b, directions[k], settings.relativeCfm, friction, out);
    return normalIndex;
}

ContactView viewOf(const Contact& c) {
    return {c.bodyA,
            c.bodyB,
            c.point,
            c.point,
            c.normal,
            c.depth,
            c.friction,
            c.restitution,
            c.approachVelocity ? &*c.approachVelocity : nullptr,
            c.frictionDirection ? &*c.frictionDirection : nullptr};
}

Mat3 inverseInertiaOf(int body, std::span<const RigidBody> bodies) {
    return body == kWorldBody ? Mat3::Zero() : bodies[static_cast<std::size_t>(body)].inverseInertiaWorld();
}

// The world's is never read (sideOf leaves it out), so any matrix serves and no static needs
// a guard on every call.
const Mat3& inverseInertiaOf(int body, std::span<const Mat3> inverseInertiaWorld) {
    return body == kWorldBody ? inverseInertiaWorld[0] : inverseInertiaWorld[static_cast<std::size_t>(body)];
}

}  // namespace

int frictionDirections(const Vec3& n, const Vec3* frictionDirection, Vec3 (&out)[2]) {
    if (frictionDirection) {
        const Vec3 along = *frictionDirection - n * n.dot(*frictionDirection);
        if (along.norm() > 1e-9) {
            out[0] = along.normalized();
            return 1;
        }
    }
    tangents(n, out[0], out[1]);
    return 2;
}

int writeContactRows(const Contact& c, std::span<const RigidBody> bodies, const ContactSettings& settings,
                     ConstraintRows& out) {
    const Mat3 a = inverseInertiaOf(c.bodyA, bodies);
    const Mat3 b = inverseInertiaOf(c.bodyB, bodies);
    return writeRows(viewOf(c), bodies, a, b, settings, out);
}

int writeContactRows(const Contact& c, std::span<const RigidBody> bodies, std::span<const Mat3> inverseInertiaWorld,
                     const ContactSettings& settings, ConstraintRows& out) {
    return writeRows(viewOf(c), bodies, inverseInertiaOf(c.bodyA, inverseInertiaWorld),
                                     inverseInertiaOf(c.bodyB, inverseInertiaWorld), settings, out);
}

void writeContactRows(std::span<const ContactPoint> points, std::span<const RigidBody> bodies,
                      std::span<const Mat3> inverseInertiaWorld, const ContactSettings& settings, ConstraintRows& rows,
                      std::vector<std::uint64_t>& keys, bool placedHold) {
    using contact_detail::bodyOrNull;
    using contact_detail::toWorld;
    // A manifold's points share its normal, and so their tangents: computed once per run of them.
    Vec3 tangentsOfNormal[2];
    Vec3 normalOfTangents = Vec3::Zero();  // no unit normal equals it
    for (const ContactPoint& p : points) {
        const RigidBody* a = bodyOrNull(bodies, p.bodyA);
        const bool placed = placedHold && p.placed;
        const Vec3 onA = placed ? p.onA : toWorld(a, p.localA);
        const Vec3 onB = placed ? p.onB : toWorld(bodyOrNull(bodies, p.bodyB), p.localB);
        ContactView c;
        c.bodyA = p.bodyA;
        c.bodyB = p.bodyB;
        c.pointA = onA;
        c.pointB = onB;
        c.normal = p.normal;
        c.depth = -p.normal.dot(onA - onB);
        c.friction = p.friction;
        c.restitution = p.restitution;
        c.approachVelocity = &p.approachVelocity;
        if (p.friction > 0 && !p.frictionDirection) {
            if (p.normal != normalOfTangents) {
                tangents(p.normal, tangentsOfNormal[0], tangentsOfNormal[1]);
                normalOfTangents = p.normal;
            }
            c.tangents = tangentsOfNormal;
        }
        Vec3 frictionDirection;
        if (p.frictionDirection) {
            frictionDirection = a->orientation * *p.frictionDirection;
            c.frictionDirection = &frictionDirection;
        }
        const std::size_t first = rows.size();
        writeRows(c, bodies, inverseInertiaOf(p.bodyA, inverseInertiaWorld),
                                  inverseInertiaOf(p.bodyB, inverseInertiaWorld), settings, rows);
        for (std::size_t r = first; r < rows.size(); ++r) keys.push_back(p.key + (r - first));
    }
}

}  // namespace af
