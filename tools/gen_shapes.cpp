// af-gen's shapes and masses: each body a box or a cylinder along its bone, sized from the
// vertices weighted mostly to its joints (docs/af-gen.md, "Shapes").

#include "gen_figure.h"

#include <algorithm>
#include <cmath>

namespace af::gen {

namespace {

// With fewer vertices than this a body is sized from its bone.
constexpr int kMinVertices = 8;
// A bone-sized body's half-width: this fraction of its bone (our humanoid's limbs are 0.3 to 0.4
// of their length across), and never under kMinRadiusFraction of the figure's size.
constexpr Real kRadiusFraction = 0.2;
constexpr Real kMinRadiusFraction = 0.02;
// No side of a shape under a quarter of its longest: the principal moments then stay within 16:1,
// below figure_checks' 20:1 warning.
constexpr Real kMinAspect = 0.25;
// Masses across a joint within 8:1, well inside figure_checks' 20:1 warning.
constexpr Real kMaxMassRatio = 8;
// A child more than 60° off the bone coming in does not carry that bone on.
constexpr Real kGoesOnCos = 0.5;
// An end body whose flesh reaches this share of its farthest point's distance along the bone
// coming in carries that bone on (our humanoid's head: all of it; its foot: 2 of 6.3, no).
constexpr Real kGoesOnShare = 0.4;
// Cross-sections rounder than this (larger over smaller side) are cylinders.
constexpr Real kCylinderAspect = 1.6;
constexpr int kCylinderSides = 8;
// A trunk body sized from its bones: its half-width 0.7 of the trunk's (how far its limbs start
// from it), 0.5 at its end (a head), and 0.6 of that front to back. Our humanoid's hand-made
// pelvis, waist and chest are 12 to 16 wide and 8 to 9 deep, its head 8 by 6.5, for shoulders
// 16 apart.
constexpr Real kTrunkShare = 0.7;
constexpr Real kTrunkEndShare = 0.5;
constexpr Real kTrunkDepth = 0.6;
// Our humanoid (af/humanoid.af): 150 mass units for a figureSize of 69, its toes (z 1) to the
// top of its head (z 70).
constexpr Real kHumanoidMass = 150;
constexpr Real kHumanoidSize = 69;


Vec3 joint(const Skeleton& pose, int j) { return pose.joints[static_cast<std::size_t>(j)].position; }

int subtreeSize(const Skeleton& pose, int j) {
    int count = 1;
    for (std::size_t k = static_cast<std::size_t>(j) + 1; k < pose.size(); ++k) {
        int p = pose.parents[k];
        while (p > j) p = pose.parents[static_cast<std::size_t>(p)];
        if (p == j) ++count;
    }
    return count;
}

// A right-handed frame with z along `axis` and x as near the figure's forward as it can be.
Mat3 boneFrame(const Vec3& axis) {
    Vec3 x = kForward - kForward.dot(axis) * axis;
    if (x.norm() < 0.3) x = kUp - kUp.dot(axis) * axis;
    x.normalize();
    Mat3 r;
    r << x, axis.cross(x), axis;
    return r;
}

// Where the body's bone ends: at its main child body's joint, else at the farthest of its own
// joints and vertices. The main child goes on the way the body's own bone came in (a chest's
// neck, not its arms, though an arm holds more joints); the root body, with no bone coming in,
// goes on to the child that carries most of the skeleton (a pelvis's spine).
Vec3 boneEnd(const std::vector<GenBody>& bodies, const GenBody& body, const Skeleton& pose,
             const std::vector<Vec3>& vertices) {
    const Vec3 start = joint(pose, body.joint);
    if (!body.children.empty()) {
        const int parentJoint = pose.parents[static_cast<std::size_t>(body.joint)];
        Vec3 in = parentJoint >= 0 ? Vec3(start - joint(pose, parentJoint)) : Vec3(Vec3::Zero());
        if (body.parent < 0 || in.norm() < 1e-9) in = Vec3::Zero();
        else in.normalize();
        // How straight on a child goes, in tenths (so that near ties fall to the larger
        // subtree), then how much of the skeleton it carries.
        const auto score = [&](int child) {
            const int j = bodies[static_cast<std::size_t>(child)].joint;
            const Vec3 out = joint(pose, j) - start;
            const Real along = out.norm() > 1e-9 ? in.dot(out.normalized()) : -1;
            return std::pair(in.isZero() ? 0.0 : std::round(along * 10), subtreeSize(pose, j));
        };
        const auto main = std::max_element(body.children.begin(), body.children.end(),
                                           [&](int a, int b) { return score(a) < score(b); });
        const Vec3 mainJoint = joint(pose, bodies[static_cast<std::size_t>(*main)].joint);
        if (body.children.size() == 1 || in.isZero() || in.dot((mainJoint - start).normalized()) >= kGoesOnCos)
            return mainJoint;
        // Every one of several children branches off (the last segment of a centipede, between
        // its legs; not a thigh, whose one child is its knee however it turns): the bone
        // goes on the way it came, over the body's own joints and vertices, at least half as
        // long as the bone before it.
        Real length = 0.5 * (start - joint(pose, parentJoint)).norm();
        for (int j : body.joints)
            if (j > body.joint) length = std::max(length, in.dot(joint(pose, j) - start));
        for (const Vec3& v : vertices) length = std::max(length, in.dot(v - start));
        return start + length * in;
    }
    Vec3 end = start;
    for (int j : body.joints)
        if (j > body.joint && (joint(pose, j) - start).norm() > (end - start).norm()) end = joint(pose, j);
    for (const Vec3& v : vertices)
        if ((v - start).norm() > (end - start).norm()) end = v;
    // An end that reaches on the way the bone came in (a head on its neck) goes on exactly that
    // way, so that the body starts square across its parent's end, not slanted into it; its
    // farthest point may be a ponytail or a jaw. One that mostly turns off (a foot) goes to its
    // farthest point.
    const int parentJoint = pose.parents[static_cast<std::size_t>(body.joint)];
    if (body.parent < 0 || parentJoint < 0 || (end - start).norm() < 1e-9) return end;
    const Vec3 in = start - joint(pose, parentJoint);
    if (in.norm() < 1e-9) return end;
    const Vec3 d = in.normalized();
    Real length = 0;
    for (int j : body.joints)
        if (j > body.joint) length = std::max(length, d.dot(joint(pose, j) - start));
    for (const Vec3& v : vertices) length = std::max(length, d.dot(v - start));
    return length >= kGoesOnShare * (end - start).norm() ? Vec3(start + length * d) : end;
}

// `across`: a trunk body's half-width when it is sized from its bone (0: from its bone's length).
GenShape shapeOf(const std::vector<GenBody>& bodies, const GenBody& body, const Skeleton& pose,
                 const std::vector<Vec3>& vertices, Real size, Real across) {
    const Vec3 start = joint(pose, body.joint);
    Vec3 bone = body.boneEnd - start;
    if (bone.norm() < 1e-6 * size) {
        // A lone joint with nothing beyond it: carry on its parent's bone, half as long.
        const int p = pose.parents[static_cast<std::size_t>(body.joint)];
        const Vec3 parentBone = p >= 0 ? Vec3(start - joint(pose, p)) : Vec3(Vec3::Zero());
        bone = parentBone.norm() > 1e-6 * size ? Vec3(0.5 * parentBone) : Vec3(0.1 * size * kUp);
    }
    const Real length = bone.norm();
    GenShape shape;
    shape.rotation = boneFrame(bone / length);
    const Mat3 toLocal = shape.rotation.transpose();
    const Real radius = std::max(kRadiusFraction * length, kMinRadiusFraction * size);

    Vec3 lo(0, 0, 0), hi(0, 0, length);
    const auto grow = [&](const Vec3& p) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    };
    const bool fromMesh = static_cast<int>(vertices.size()) >= kMinVertices;
    if (fromMesh) {
        shape.meshVertices = static_cast<int>(vertices.size());
        for (const Vec3& v : vertices) {
            Vec3 local = toLocal * (v - start);
            // Behind the joint is the parent's flesh (round a hip, a shoulder): a body that starts
            // at its joint never starts inside its parent (figure_checks' 20 % overlap warning).
            local.z() = std::max(local.z(), Real(0));
            // Beyond the main child's joint the vertices are that child's flesh.
            if (!body.children.empty()) local.z() = std::min(local.z(), length);
            grow(local);
        }
    } else if (across > radius) {
        // Across the figure (the frame's y) as wide as the trunk, front to back shallower.
        grow(Vec3(-kTrunkDepth * across, -across, 0));
        grow(Vec3(kTrunkDepth * across, across, length));
    } else {
        grow(Vec3(-radius, -radius, 0));
        grow(Vec3(radius, radius, length));
    }
    // The body's own joints (a clavicle, a toe) inside it; its other children's joints on its
    // surface, where their bodies start.
    for (int j : body.joints) {
        // Joints above the body's own (the root body's `origin`, on the floor) are not its flesh;
        // those behind its joint (a jaw under a head) widen it but do not take it into its parent.
        if (j < body.joint) continue;
        Vec3 local = toLocal * (joint(pose, j) - start);
        local.z() = std::max(local.z(), Real(0));
        grow(local + Vec3(radius, radius, 0));
        grow(local - Vec3(radius, radius, 0));
    }
    for (int c : body.children) grow(toLocal * (joint(pose, bodies[static_cast<std::size_t>(c)].joint) - start));

    // Stout enough for figure_checks' inertia warning.
    const Vec3 extent = hi - lo;
    const Real least = kMinAspect * extent.maxCoeff();
    for (int k = 0; k < 3; ++k) {
        // Across the bone both ways; along it only onward, away from the parent.
        const Real grown = std::max(0.0, least - extent[k]) / (k == 2 ? 1 : 2);
        lo[k] -= k == 2 ? 0 : grown;
        hi[k] += grown;
    }
    shape.lower = lo;
    shape.upper = hi;
    const Vec3 section = hi - lo;
    const Real roundness = std::max(section.x(), section.y()) / std::min(section.x(), section.y());
    shape.type = body.children.size() <= 1 && roundness < kCylinderAspect ? ShapeType::Cylinder : ShapeType::Box;
    return shape;
}

Real volumeOf(const GenShape& shape) {
    const Vec3 size = shape.upper - shape.lower;
    const Real box = size.x() * size.y() * size.z();
    if (shape.type == ShapeType::Box) return box;
    // An n-gon inscribed in the ellipse of the box's section (docs/figures.md §3.3).
    const Real pi = std::acos(Real(-1));
    return box * (kCylinderSides / 8.0) * std::sin(2 * pi / kCylinderSides);
}

}  // namespace

Real defaultTotalMass(const Skeleton& pose, const std::vector<MeshPoint>& points) {
    const Real scale = figureSize(pose, points) / kHumanoidSize;
    return kHumanoidMass * scale * scale * scale;
}

void sizeBodies(std::vector<GenBody>& bodies, const Skeleton& pose, const std::vector<MeshPoint>& points,
                Real totalMass) {
    const Real size = figureSize(pose, points);

    std::vector<int> bodyOf(pose.size(), 0);
    for (std::size_t b = 0; b < bodies.size(); ++b)
        for (int j : bodies[b].joints) bodyOf[static_cast<std::size_t>(j)] = static_cast<int>(b);
    std::vector<std::vector<Vec3>> vertices(bodies.size());
    for (const MeshPoint& p : points)
        vertices[static_cast<std::size_t>(bodyOf[static_cast<std::size_t>(p.joint)])].push_back(p.position);

    for (std::size_t b = 0; b < bodies.size(); ++b) bodies[b].boneEnd = boneEnd(bodies, bodies[b], pose, vertices[b]);

    // The trunk: the root body and, on from it, each trunk body's main child (a pelvis, waist,
    // chest and head; a chain's every link). Its half-width is the farthest its limbs start
    // from its bones (our humanoid's shoulders, 8 units out).
    std::vector<bool> trunk(bodies.size(), false);
    Real trunkHalfWidth = 0;
    for (std::size_t b = 0; b < bodies.size(); ++b) {
        const GenBody& body = bodies[b];
        trunk[b] = body.parent < 0 || (trunk[static_cast<std::size_t>(body.parent)] &&
                                       (joint(pose, body.joint) - bodies[static_cast<std::size_t>(body.parent)].boneEnd)
                                               .norm() < 1e-9);
        const Vec3 bone = body.boneEnd - joint(pose, body.joint);
        if (!trunk[b] || bone.norm() < 1e-9) continue;
        const Vec3 d = bone.normalized();
        for (int c : body.children) {
            const Vec3 out = joint(pose, bodies[static_cast<std::size_t>(c)].joint) - joint(pose, body.joint);
            trunkHalfWidth = std::max(trunkHalfWidth, (out - out.dot(d) * d).norm());
        }
    }

    Real volume = 0;
    for (std::size_t b = 0; b < bodies.size(); ++b) {
        const Real across = !trunk[b] ? 0 : (bodies[b].children.empty() ? kTrunkEndShare : kTrunkShare) * trunkHalfWidth;
        bodies[b].shape = shapeOf(bodies, bodies[b], pose, vertices[b], size, across);
        volume += volumeOf(bodies[b].shape);
    }
    // One density for the whole figure, then each body (parents come first) kept near its parent.
    for (GenBody& body : bodies) {
        body.mass = totalMass * volumeOf(body.shape) / volume;
        if (body.parent < 0) continue;
        const Real parent = bodies[static_cast<std::size_t>(body.parent)].mass;
        body.mass = std::clamp(body.mass, parent / kMaxMassRatio, parent * kMaxMassRatio);
    }
    Real sum = 0;
    for (const GenBody& body : bodies) sum += body.mass;
    for (GenBody& body : bodies) body.mass *= totalMass / sum;
}

// Density is what a .af file holds; volumeOf gives the shape's volume as the builder computes it.
Real densityOf(const GenBody& body) { return body.mass / volumeOf(body.shape); }

}  // namespace af::gen
