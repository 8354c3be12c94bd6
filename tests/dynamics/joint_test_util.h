#pragma once
// Two-body figures with one constraint, random poses and velocities, and moving bodies along
// their velocities, for the joint tests.

#include "af/figure/figure.h"
#include "dynamics/joint_rows.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace af::test {

inline constexpr Real kPi = std::numbers::pi_v<Real>;
inline Real rad(Real degrees) { return degrees * kPi / 180; }
inline Real deg(Real radians) { return radians * 180 / kPi; }
// A rotation by `degrees` about `axis` (of any length).
inline Quat turn(const Vec3& axis, Real degrees) { return Quat(Eigen::AngleAxis<Real>(rad(degrees), axis.normalized())); }

// A figure of two bodies (A = body 0, B = body 1) with the given spawn poses and one constraint.
// `c.body2` decides whether B or the world is the second body.
inline Figure twoBodyFigure(const RigidPose& a, const RigidPose& b, const FigureConstraint& c) {
    Figure f;
    FigureBody bodyA, bodyB;
    bodyA.name = "a";
    bodyA.pose = a;
    bodyA.mass = 2;
    bodyB.name = "b";
    bodyB.pose = b;
    bodyB.mass = 3;
    f.bodies = {bodyA, bodyB};
    f.constraints = {c};
    return f;
}

inline FigureConstraint constraintOf(ConstraintType type, int body2 = 1) {
    FigureConstraint c;
    c.type = type;
    c.name = "joint";
    c.body1 = 0;
    c.body2 = body2;
    return c;
}

inline RigidBody bodyAt(const RigidPose& pose, Real mass = 2) {
    RigidBody b;
    b.position = pose.position;
    b.orientation = Quat(pose.rotation).normalized();
    b.inverseMass = 1 / mass;
    b.inertia = Mat3::Identity() * mass * 4;
    b.inverseInertia = b.inertia.inverse();
    return b;
}

// Bodies at the figure's spawn poses, at rest.
inline std::vector<RigidBody> spawnBodies(const Figure& f) {
    std::vector<RigidBody> out;
    for (const FigureBody& b : f.bodies) out.push_back(bodyAt(b.pose));
    return out;
}

class Random {
public:
    explicit Random(unsigned seed) : engine_(seed) {}
    Real uniform(Real lo, Real hi) { return std::uniform_real_distribution<Real>(lo, hi)(engine_); }
    Vec3 vector(Real size) { return Vec3(uniform(-size, size), uniform(-size, size), uniform(-size, size)); }
    Vec3 direction() {
        for (;;) {
            const Vec3 v = vector(1);
            if (v.norm() > Real(0.1) && v.norm() <= 1) return v.normalized();
        }
    }
    Quat rotation() {
        return Quat(Eigen::AngleAxis<Real>(uniform(0, kPi), direction()));
    }
    // A rotation by at most `maxAngle` radians.
    Quat turn(Real maxAngle) { return Quat(Eigen::AngleAxis<Real>(uniform(0, maxAngle), direction())); }
    RigidPose pose(Real size) { return {vector(size), rotation().toRotationMatrix()}; }

private:
    std::mt19937_64 engine_;
};

// A constraint of the type with random anchors, axis, shafts (opposite, so that a universal
// joint starts untwisted) and limit axis; limits, lengths and friction are the caller's.
inline FigureConstraint randomConstraint(ConstraintType type, int body2, Random& random) {
    FigureConstraint c = constraintOf(type, body2);
    c.anchor = random.vector(3);
    c.anchor2 = random.vector(3);
    c.axis = random.direction();
    c.shafts[0] = random.direction();
    c.shafts[1] = -c.shafts[0];
    c.limitAxis = random.direction();
    return c;
}

// The body moved for time t along its current (constant) velocities: exact rotation about ω.
inline RigidBody advanced(const RigidBody& b, Real t) {
    RigidBody out = b;
    out.position = b.position + t * b.linearVelocity;
    const Real speed = b.angularVelocity.norm();
    if (speed > 0) out.orientation = (Quat(Eigen::AngleAxis<Real>(t * speed, b.angularVelocity / speed)) * b.orientation).normalized();
    return out;
}

inline std::vector<RigidBody> advanced(const std::vector<RigidBody>& bodies, Real t) {
    std::vector<RigidBody> out;
    for (const RigidBody& b : bodies) out.push_back(advanced(b, t));
    return out;
}

// Cdot of a row at the bodies' velocities.
inline Real rowVelocity(const ConstraintRow& row, const std::vector<RigidBody>& bodies) {
    Real cdot = 0;
    if (row.bodyA >= 0) {
        const RigidBody& a = bodies[static_cast<std::size_t>(row.bodyA)];
        cdot += row.linearA.dot(a.linearVelocity) + row.angularA.dot(a.angularVelocity);
    }
    if (row.bodyB >= 0) {
        const RigidBody& b = bodies[static_cast<std::size_t>(row.bodyB)];
        cdot += row.linearB.dot(b.linearVelocity) + row.angularB.dot(b.angularVelocity);
    }
    return cdot;
}

// Turns body `index` (world-frame rotation about its centre of mass) by `turn`.
inline void turnBody(std::vector<RigidBody>& bodies, int index, const Quat& turn) {
    RigidBody& b = bodies[static_cast<std::size_t>(index)];
    b.orientation = (turn * b.orientation).normalized();
}

// Turns body `index` by `turn` about the world point `pivot`.
// The constraint's joint (last impulse 1, so that joint friction has a bound) between two bodies
// at random poses, body 0 then turned and moved off the joint's rest a little.
struct PosedJoint {
    Joint joint;
    std::vector<RigidBody> bodies;
};
inline PosedJoint posedJoint(const FigureConstraint& c, Random& random) {
    const Figure f = twoBodyFigure(random.pose(3), random.pose(3), c);
    PosedJoint out{makeJoints(f).at(0), spawnBodies(f)};
    out.joint.lastImpulse = 1;
    turnBody(out.bodies, 0, random.turn(1));
    out.bodies[0].position += random.vector(1);
    return out;
}

inline void turnBodyAbout(std::vector<RigidBody>& bodies, int index, const Quat& turn, const Vec3& pivot) {
    RigidBody& b = bodies[static_cast<std::size_t>(index)];
    b.position = pivot + turn * (b.position - pivot);
    b.orientation = (turn * b.orientation).normalized();
}

// Body A hangs 10 below the world anchor at the origin.
inline const RigidPose kHanging{Vec3(0, 0, -10), Mat3::Identity()};

// A ball joint holding A to the world at the origin, its limit about −Z (A's shaft, hanging).
inline Joint hangingBall(LimitType limit, Real3 angles) {
    FigureConstraint c = constraintOf(ConstraintType::BallAndSocket, kWorld);
    c.anchor = Vec3::Zero();
    c.limit = limit;
    c.limitAxis = Vec3(0, 0, -1);
    c.shafts[0] = Vec3(0, 0, -1);
    c.limitAngles = angles;
    return makeJoints(twoBodyFigure(kHanging, {}, c)).at(0);
}

inline JointRowSettings allLimitRows() {
    JointRowSettings s;
    s.limitMargin = kInfinity;
    s.springLimitMargin = kInfinity;
    return s;
}

}  // namespace af::test
