// Bodies drive the skeleton (docs/figures.md §3.6), in one frame: world space throughout.
// Doom mixes model and world space for `position` and `both` bodies (docs/doom-quirks.md item 19); we do not.

#include "af/figure/figure.h"

namespace af {

Skeleton poseSkeleton(const Figure& figure, const std::vector<RigidPose>& bodyPoses) {
    Skeleton out = figure.afPose;
    const std::size_t n = out.size();
    if (n == 0 || bodyPoses.empty()) return out;

    // The entity moves as body 0 has moved since spawn; undriven joints hang off it.
    const RigidPose spawnModelPose0 = figure.placement.inverse() * figure.bodies[0].pose;
    const RigidPose entity = bodyPoses[0] * spawnModelPose0.inverse();

    std::vector<int> driver(n, -1);
    for (std::size_t b = 0; b < figure.bodies.size() && b < bodyPoses.size(); ++b)
        if (figure.bodies[b].joint >= 0) driver[static_cast<std::size_t>(figure.bodies[b].joint)] = static_cast<int>(b);

    for (std::size_t i = 0; i < n; ++i) {
        const JointTransform local = figure.afPose.local(i);
        const int p = out.parents[i];
        const RigidPose parent = p < 0 ? entity : RigidPose{out.joints[static_cast<std::size_t>(p)].position,
                                                            out.joints[static_cast<std::size_t>(p)].rotation};
        RigidPose joint = parent * RigidPose{local.position, local.rotation};
        if (driver[i] >= 0 && p >= 0) {
            const FigureBody& body = figure.bodies[static_cast<std::size_t>(driver[i])];
            const RigidPose driven = bodyPoses[static_cast<std::size_t>(driver[i])] * body.bodyInJoint.inverse();
            switch (body.mod) {
            case JointMod::Orientation: joint.rotation = driven.rotation; break;
            case JointMod::Position: joint.position = driven.position; break;
            case JointMod::Both: joint = driven; break;
            }
        }
        out.joints[i] = {joint.position, joint.rotation};
    }
    return out;
}

}  // namespace af
