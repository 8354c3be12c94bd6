// af-gen's bodies: which joints get a body, which body contains each joint (docs/af-gen.md,
// "Bodies").

#include "gen_figure.h"

#include "af/text/strings.h"

#include <algorithm>
#include <array>
#include <stdexcept>

namespace af::gen {

namespace {

// A bone shorter than this fraction of the figure's size is no body of its own (a neck of 3 units
// on a 70-unit humanoid, finger bones); 5 % keeps our humanoid's clavicles (6 units) only by name.
constexpr Real kTinyBoneFraction = 0.05;
// ... and shorter than this fraction of its parent's bone: a segment of a centipede 120 units
// long is 6, under 5 %, but as long as the segment before it.
constexpr Real kTinyAgainstParent = 0.5;

// Parts that a ragdoll does not swing on their own, whatever their size: they ride on their
// parent's body (lower-case substrings of the joint's name).
constexpr std::array kEndPartNames{"finger", "thumb", "index", "pinky", "toe", "eye", "jaw", "tongue", "lid",
                                   "brow", "lip", "teeth", "clavicle", "collar", "tag", "attach"};
// Parts that keep a body even when short (a hand with short finger bones).
constexpr std::array kMainPartNames{"hand", "foot", "head", "paw", "wrist", "ankle"};

bool listed(const std::vector<std::string>& names, const std::string& joint) {
    return std::any_of(names.begin(), names.end(), [&](const std::string& n) { return equalsIgnoreCase(n, joint); });
}

}  // namespace

Real figureSize(const Skeleton& pose, const std::vector<MeshPoint>& points) {
    Vec3 lo = Vec3::Constant(1e30), hi = Vec3::Constant(-1e30);
    for (std::size_t j = 0; j < pose.size(); ++j) {
        // The `origin` joint stands on the floor under a figure, wherever its body is (the chain
        // hangs 64 units above its origin): it is no part of the figure's size.
        if (equalsIgnoreCase(pose.names[j], "origin")) continue;
        lo = lo.cwiseMin(pose.joints[j].position);
        hi = hi.cwiseMax(pose.joints[j].position);
    }
    for (const MeshPoint& p : points) {
        lo = lo.cwiseMin(p.position);
        hi = hi.cwiseMax(p.position);
    }
    return hi.x() >= lo.x() ? std::max((hi - lo).maxCoeff(), Real(1)) : Real(1);
}

int rootJoint(const Skeleton& skeleton) {
    // The builder's rule (src/figure/figure_builder.cpp, drivenJoint): the first child of
    // `origin`, or of the skeleton's root when no joint has that name.
    const int origin = std::max(skeleton.find("origin"), 0);
    for (std::size_t j = 0; j < skeleton.size(); ++j)
        if (skeleton.parents[j] == origin) return static_cast<int>(j);
    throw std::invalid_argument("the joint \"" + skeleton.names[static_cast<std::size_t>(origin)] +
                                "\" has no child for the root body to drive (docs/figures.md §3.6)");
}

std::vector<MeshPoint> meshPoints(const std::vector<Md5SkinSection>& skin, const Skeleton& afPose) {
    std::vector<MeshPoint> points;
    for (const Md5SkinSection& section : skin) {
        for (const Md5Vertex& vertex : section.vertices) {
            MeshPoint point;
            Real heaviest = -1;
            for (int w = vertex.firstWeight; w < vertex.firstWeight + vertex.weightCount; ++w) {
                const Md5Weight& weight = section.weights[static_cast<std::size_t>(w)];
                const JointTransform& joint = afPose.joints[static_cast<std::size_t>(weight.joint)];
                const Vec3 offset(weight.position[0], weight.position[1], weight.position[2]);
                point.position += weight.bias * (joint.position + joint.rotation * offset);
                if (weight.bias > heaviest) {
                    heaviest = weight.bias;
                    point.joint = weight.joint;
                }
            }
            points.push_back(point);
        }
    }
    return points;
}

std::vector<GenBody> groupJoints(const Skeleton& pose, const std::vector<MeshPoint>& points, const GenOptions& options) {
    const std::size_t n = pose.size();
    for (const std::string& name : pose.names)
        if (equalsIgnoreCase(name, "world"))
            throw std::invalid_argument("a joint is named \"world\", which no body may be called (docs/formats.md §1.6)");
    for (const std::vector<std::string>* list : {&options.keep, &options.merge})
        for (const std::string& name : *list) {
            if (pose.find(name) < 0) throw std::invalid_argument("--keep/--merge: no joint is named \"" + name + "\"");
            if (listed(options.keep, name) && listed(options.merge, name))
                throw std::invalid_argument("the joint \"" + name + "\" is both kept and merged");
        }
    const int root = rootJoint(pose);
    std::vector<int> weighted(n, 0);
    for (const MeshPoint& p : points) ++weighted[static_cast<std::size_t>(p.joint)];

    // A joint's bone: from it to its farthest child, or across its vertices when it has none.
    std::vector<Real> bone(n, 0);
    std::vector<int> childCount(n, 0);
    for (std::size_t j = 1; j < n; ++j) {
        const auto p = static_cast<std::size_t>(pose.parents[j]);
        ++childCount[p];
        bone[p] = std::max(bone[p], (pose.joints[j].position - pose.joints[p].position).norm());
    }
    for (const MeshPoint& p : points) {
        const auto j = static_cast<std::size_t>(p.joint);
        if (childCount[j] == 0) bone[j] = std::max(bone[j], (p.position - pose.joints[j].position).norm());
    }
    const Real tiny = kTinyBoneFraction * figureSize(pose, points);

    std::vector<int> bodyOf(n, -1);
    std::vector<GenBody> bodies(1);
    bodies[0].name = pose.names[static_cast<std::size_t>(root)];
    bodies[0].joint = root;
    bodyOf[static_cast<std::size_t>(root)] = 0;
    for (std::size_t j = 0; j < n; ++j) {
        if (static_cast<int>(j) == root) continue;
        const std::string lower = toLower(pose.names[j]);
        const bool below = pose.parents[j] >= 0 && bodyOf[static_cast<std::size_t>(pose.parents[j])] >= 0;
        // The `origin` joint is the root body's by the format's rule (docs/figures.md §3.6).
        bool own = below && (childCount[j] > 0 || weighted[j] > 0) && !equalsIgnoreCase(lower, "origin");
        if (own && nameHas(lower, kEndPartNames)) own = false;
        // Tiny: short for the figure, and beside its parent's bone (a neck under a chest, not the
        // even segments of a long body) or under a joint that is no body of its own (the second
        // bone of a ponytail whose first was tiny).
        const int parent = pose.parents[j];
        const auto p = static_cast<std::size_t>(parent);
        const bool parentOwn = below && bodies[static_cast<std::size_t>(bodyOf[p])].joint == parent;
        const bool shortHere = !parentOwn || bone[j] < kTinyAgainstParent * bone[p];
        if (own && bone[j] < tiny && shortHere && !nameHas(lower, kMainPartNames)) own = false;
        if (below && listed(options.keep, pose.names[j])) own = true;
        if (listed(options.merge, pose.names[j])) own = false;
        const int parentBody = below ? bodyOf[p] : 0;
        if (!own) {
            bodyOf[j] = parentBody;
            continue;
        }
        bodyOf[j] = static_cast<int>(bodies.size());
        GenBody& body = bodies.emplace_back();
        body.name = pose.names[j];
        body.joint = static_cast<int>(j);
        body.parent = parentBody;
    }
    for (std::size_t j = 0; j < n; ++j) bodies[static_cast<std::size_t>(bodyOf[j])].joints.push_back(static_cast<int>(j));
    for (std::size_t b = 1; b < bodies.size(); ++b)
        bodies[static_cast<std::size_t>(bodies[b].parent)].children.push_back(static_cast<int>(b));
    return bodies;
}

}  // namespace af::gen
