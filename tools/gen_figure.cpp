// af-gen's decl: the bodies and constraints of gen_bodies, gen_shapes and gen_constraints as the
// .af data the parser would produce, so that the canonical writer prints it (docs/formats.md §1.10).

#include "gen_figure.h"

#include "af/geometry/math.h"

#include <cmath>

namespace af::gen {

namespace {

Real toFloat(Real x) { return static_cast<float>(std::fabs(x) < 1e-6 ? 0 : x); }

}  // namespace

AFVector literal(const Vec3& v) { return AFVector::literal(toFloat(v.x()), toFloat(v.y()), toFloat(v.z())); }

namespace {

// A containedJoints list (docs/formats.md §1.6) naming each of the body's joints once: `*name`
// where the joints that form expands to (the run after it in skeleton order whose parents do not
// come before it, as Doom reads it: not always the whole subtree) are all the body's, the bare
// name for the others.
std::string containedJoints(const GenBody& body, const Skeleton& pose, const std::vector<int>& bodyOf, int self) {
    const std::size_t n = pose.size();
    std::string list;
    std::vector<bool> covered(n, false);
    for (int j : body.joints) {
        const auto k = static_cast<std::size_t>(j);
        if (covered[k]) continue;
        std::size_t end = k + 1;
        while (end < n && pose.parents[end] >= j) ++end;
        bool whole = end > k + 1;
        for (std::size_t m = k; m < end && whole; ++m) whole = bodyOf[m] == self;
        for (std::size_t m = k; m < (whole ? end : k + 1); ++m) covered[m] = true;
        list += (list.empty() ? "" : " ") + std::string(whole ? "*" : "") + pose.names[k];
    }
    return list;
}

AFBody makeBody(const GenBody& body, const Skeleton& pose, const std::vector<int>& bodyOf, int self) {
    AFBody b;
    b.name = body.name;
    // The root body drives the `origin` joint's child by the format's rule (docs/figures.md §3.6).
    b.joint = self == 0 ? "origin" : body.name;
    b.shape.type = body.shape.type;
    b.shape.v1 = literal(body.shape.lower);
    b.shape.v2 = literal(body.shape.upper);
    b.shape.numSides = 8;
    AFVector origin;
    origin.kind = AFVector::Kind::Joint;
    origin.joint1 = body.name;
    b.origin = origin;
    const Vec3 angles = anglesFromRotationPrecise(body.shape.rotation);
    b.angles = {toFloat(angles.x()), toFloat(angles.y()), toFloat(angles.z())};
    b.density = static_cast<float>(densityOf(body));
    const AFSettings defaults;
    b.linearFriction = defaults.linearFriction;
    b.angularFriction = defaults.angularFriction;
    b.contactFriction = defaults.contactFriction;
    b.contents = defaults.contents;
    b.clipMask = defaults.clipMask | contents::MoveableClip;
    b.containedJoints = containedJoints(body, pose, bodyOf, self);
    return b;
}

}  // namespace

Generated generateFigure(const std::vector<Md5SkinSection>& skin, const Skeleton& afPose, const GenOptions& options) {
    Generated g;
    const std::vector<MeshPoint> points = meshPoints(skin, afPose);
    g.totalMass = options.totalMass > 0 ? options.totalMass : defaultTotalMass(afPose, points);
    g.totalMass = static_cast<float>(g.totalMass);
    g.bodies = groupJoints(afPose, points, options);
    sizeBodies(g.bodies, afPose, points, g.totalMass);

    std::vector<int> bodyOf(afPose.size(), 0);
    for (std::size_t b = 0; b < g.bodies.size(); ++b)
        for (int j : g.bodies[b].joints) bodyOf[static_cast<std::size_t>(j)] = static_cast<int>(b);

    g.decl.name = options.name;
    g.decl.settings.model = options.name;
    g.decl.settings.totalMass = g.totalMass;
    g.kinds.resize(g.bodies.size(), JointKind::Continuation);
    for (std::size_t b = 0; b < g.bodies.size(); ++b) {
        g.decl.bodies.push_back(makeBody(g.bodies[b], afPose, bodyOf, static_cast<int>(b)));
        if (b == 0) continue;
        g.kinds[b] = classifyJoint(g.bodies, afPose, static_cast<int>(b));
        g.decl.constraints.push_back(makeConstraint(g.bodies, afPose, static_cast<int>(b), g.kinds[b]));
    }
    return g;
}

}  // namespace af::gen
