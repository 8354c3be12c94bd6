#pragma once
// Row-level scenes for the solvers' tests: a figure's bodies, joints and hand-made contacts with
// their rows written as World writes them (joints' rows in order, then the contacts'), stepped
// with the tree solver, and the dense exact answer (RowSystem + LcpExactSolver) to compare with.

#include "../figure/figure_test_util.h"
#include "dynamics/contact_rows.h"
#include "dynamics/row_system.h"
#include "dynamics/tree_solver.h"
#include "scene_test_util.h"

#include <algorithm>
#include <random>

namespace af::test {

inline constexpr Real kDt = Real(1) / 60;
inline const Vec3 kGravity(0, 0, -1066);

inline std::vector<RigidBody> bodiesOf(const Figure& figure) {
    std::vector<RigidBody> out;
    for (const FigureBody& b : figure.bodies)
        out.push_back(RigidBody::dynamic(b.mass, b.inertia, b.pose.position, Quat(b.pose.rotation)));
    return out;
}

// A square of four bars joined by ball joints, pinned to the world at the middle of its top bar
// (hang) and off the middle of its bottom bar (ground: a second path to the world; at the middle
// the two pins would make the square's rows dependent), closed by `loop`. Below the bottom bar
// a hinge, a universal joint and a slider (written parent first, body1 = the parent), and a
// spring to the world.
inline Figure loopFigure() {
    using test::boxBodyText;
    const Vec3 across(5, 1, 1), down(1, 1, 5);
    return test::figureOfBlocks(
        {"origin", "j1", "j2", "j3", "j4", "j5", "j6"},
        boxBodyText("b0", "origin", across, Vec3(5, 0, 0), 0.2) + boxBodyText("b1", "j1", down, Vec3(10, 0, -5), 0.2) +
            boxBodyText("b2", "j2", across, Vec3(5, 0, -10), 0.2) + boxBodyText("b3", "j3", down, Vec3(0, 0, -5), 0.2) +
            boxBodyText("b4", "j4", down, Vec3(5, 0, -15), 0.2) + boxBodyText("b5", "j5", down, Vec3(5, 0, -25), 0.2) +
            boxBodyText("b6", "j6", down, Vec3(5, 0, -35), 0.2) +
            "ballAndSocketJoint \"hang\" { body1 \"b0\" body2 \"world\" anchor ( 5, 0, 0 ) friction 0 }\n"
            "ballAndSocketJoint \"j1\" { body1 \"b1\" body2 \"b0\" anchor ( 10, 0, 0 ) friction 0 }\n"
            "ballAndSocketJoint \"j2\" { body1 \"b2\" body2 \"b1\" anchor ( 10, 0, -10 ) friction 0 }\n"
            "ballAndSocketJoint \"j3\" { body1 \"b3\" body2 \"b2\" anchor ( 0, 0, -10 ) friction 0 }\n"
            "ballAndSocketJoint \"loop\" { body1 \"b3\" body2 \"b0\" anchor ( 0, 0, 0 ) friction 0 }\n"
            "ballAndSocketJoint \"ground\" { body1 \"b2\" body2 \"world\" anchor ( 2, 0, -10 ) friction 0 }\n"
            "hinge \"knee\" { body1 \"b4\" body2 \"b2\" anchor ( 5, 0, -10 ) axis ( 0, 1, 0 ) friction 0 }\n"
            "universalJoint \"hip\" { body1 \"b5\" body2 \"b4\" anchor ( 5, 0, -20 ) shafts ( 0, 0, -1 ), ( 0, 0, 1 ) "
            "friction 0 }\n"
            "slider \"rail\" { body1 \"b5\" body2 \"b6\" axis ( 0, 0, 1 ) friction 0 }\n"
            "spring \"bungee\" { body1 \"b6\" body2 \"world\" anchor1 ( 5, 0, -40 ) anchor2 ( 5, 0, -60 ) friction 0 "
            "stretch 1 compress 0 damping 0 restLength 10 minLength 0 maxLength 30 }\n");
}

// Bodies, joints and the rows of one pose, written as World writes them: the joints' rows in
// order, then the contacts'.
struct Scene {
    std::vector<RigidBody> bodies;
    std::vector<Joint> joints;
    std::vector<Contact> contacts;
    ConstraintRows rows;
    std::vector<JointRowRange> ranges;

    explicit Scene(const Figure& figure) : bodies(bodiesOf(figure)), joints(makeJoints(figure)) {}

    void write() {
        rows.clear();
        ranges.clear();
        for (const Joint& j : joints) ranges.push_back(writeJointRows(j, bodies, JointRowSettings{}, rows));
        for (const Contact& c : contacts) writeContactRows(c, bodies, ContactSettings{}, rows);
    }
    int count(int JointRowRange::*field) const {
        int n = 0;
        for (const JointRowRange& r : ranges) n += r.*field;
        return n;
    }
};

inline void spin(Scene& scene, unsigned seed, Real speed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<Real> u(-speed, speed);
    for (RigidBody& b : scene.bodies) {
        b.angularVelocity = Vec3(u(rng), u(rng), u(rng));
        b.linearVelocity = Vec3(u(rng), u(rng), u(rng));
    }
}

// The velocity problem of a step: velocities predicted with gravity, rows at the pose.
inline void predict(Scene& scene) {
    for (RigidBody& b : scene.bodies) integrateVelocity(b, kGravity, kDt, IntegrationSettings{});
    scene.write();
}

// One step as World takes it, with the tree solver: velocities, rows, impulses, positions, then
// one pass of position projection. Returns the velocity solve's result.
inline TreeSolveResult step(Scene& scene, TreeSolver& solver) {
    predict(scene);
    solver.factor(scene.rows, scene.ranges, scene.bodies);
    const TreeSolveResult result = solver.solveVelocity(scene.rows, scene.bodies);
    solver.applyImpulses(scene.bodies);
    const std::span<const Real> lambda = solver.impulses();
    for (std::size_t k = 0; k < scene.joints.size(); ++k) {
        Real sum = 0;
        for (int r = 0; r < scene.ranges[k].equalityRows; ++r) sum += std::pow(lambda[static_cast<std::size_t>(scene.ranges[k].first + r)], 2);
        scene.joints[k].lastImpulse = std::sqrt(sum);
    }
    for (RigidBody& b : scene.bodies) integratePosition(b, kDt);
    scene.write();
    solver.factor(scene.rows, scene.ranges, scene.bodies, TreeProblems::PositionOnly);
    solver.solvePosition(scene.rows);
    solver.applyDisplacements(scene.bodies);
    return result;
}

// The dense exact answer. The position problem holds friction rows at 0, as World does.
struct Dense {
    std::vector<Real> lambda;
    std::vector<LcpRowState> states;
    LcpResult result;
    RowSystem system;
};

inline void solveDense(const Scene& scene, bool position, Dense& out) {
    ConstraintRows rows = scene.rows;
    if (position) holdFrictionAtZero(rows, scene.ranges);
    out.system.build(rows, scene.bodies);
    if (position) {
        out.system.setPositionRhs(rows);
    } else {
        out.system.setVelocityRhs(rows, scene.bodies);
    }
    LcpExactSolver solver;
    out.states.assign(rows.size(), LcpRowState::Unknown);
    out.result = solver.solve(out.system.problem(), out.system.solution(), out.states);
    out.lambda.assign(out.system.solution().begin(), out.system.solution().end());
}

inline Real largest(std::span<const Real> v) {
    Real m = 0;
    for (Real x : v) m = std::max(m, std::abs(x));
    return m;
}

// Without a joint to the world the tree is rooted at its middle link; every link touches the
// ground with friction, and one link touches the far end (a row whose two bodies meet only at
// the root).
inline Scene freeChainOnTheGround(TreeSolver& solver) {
    Scene scene(test::horizontalChain(20, 0, true));
    spin(scene, 9, 3);
    solver.setStructure(scene.bodies, scene.joints);
    for (int i = 0; i < 10; ++i) step(scene, solver);
    for (int k = 0; k < 20; ++k) {
        RigidBody& b = scene.bodies[static_cast<std::size_t>(k)];
        b.linearVelocity += Vec3(k % 2 == 0 ? 20 : -5, 0, -30);
        Contact c;
        c.bodyA = k;
        c.point = b.position + Vec3(0, 0, -1);
        c.normal = Vec3::UnitZ();
        c.depth = 0.02 * (k % 7);  // the position problem pushes the deeper ones out
        c.friction = 0.6;
        scene.contacts.push_back(c);
    }
    Contact ends;
    ends.bodyA = 0;
    ends.bodyB = 19;
    ends.point = (scene.bodies[0].position + scene.bodies[19].position) / 2;
    ends.normal = (scene.bodies[0].position - scene.bodies[19].position).normalized();
    ends.friction = 0.3;
    scene.contacts.push_back(ends);
    scene.bodies[0].linearVelocity -= 40 * ends.normal;
    scene.write();
    return scene;
}

// Contacts on the humanoid's bodies against the floor and one between two of them, all with
// friction; the bodies move into the floor and along it, so some contacts push and some slide.
// None on the chest: welded to the world, it could only be pushed out of the floor against its
// weld, an answer set by the CFM alone (λ ~ depth / CFM) and as ill-conditioned.
inline Scene humanoidWithContacts(TreeSolver& solver) {
    Scene scene(test::hungHumanoid());
    spin(scene, 11, 4);
    solver.setStructure(scene.bodies, scene.joints);
    for (int i = 0; i < 20; ++i) step(scene, solver);
    const int bodyCount = static_cast<int>(scene.bodies.size());
    const int chest = scene.joints.back().bodyA;
    for (int k = 0; k < bodyCount; k += 2) {
        if (k == chest) continue;
        RigidBody& b = scene.bodies[static_cast<std::size_t>(k)];
        b.linearVelocity += Vec3(30.0 * (k % 3) - 30, 10, -60);
        Contact c;
        c.bodyA = k;
        c.point = b.position + Vec3(1, -1, -2);
        c.normal = Vec3::UnitZ();
        c.depth = 0.03 * (k % 5);
        c.friction = k % 4 == 0 ? 0.3 : 0.9;
        scene.contacts.push_back(c);
    }
    Contact between;  // the waist (body 1) and the right foot (the last body)
    between.bodyA = 1;
    between.bodyB = bodyCount - 1;
    between.point = (scene.bodies[1].position + scene.bodies.back().position) / 2;
    between.normal = (scene.bodies[1].position - scene.bodies.back().position).normalized();
    between.friction = 0.5;
    scene.contacts.push_back(between);
    scene.bodies[1].linearVelocity -= 50 * between.normal;
    scene.write();
    return scene;
}

// Three rows of one body's joint to the world that repeat each other (two are the same) and
// carry no CFM: a matrix with no pivot for the third.
inline ConstraintRows dependentRows() {
    ConstraintRows rows;
    const Vec3 axes[] = {Vec3::UnitX(), Vec3::UnitZ(), Vec3::UnitZ()};
    for (const Vec3& axis : axes) {
        ConstraintRow row;
        row.bodyA = 0;
        row.linearA = axis;
        row.angularA = Vec3(0, 0, 5).cross(axis);
        rows.add(row);
    }
    return rows;
}

}  // namespace af::test
