#pragma once
// Baking a simulated figure into an .md5anim that id Tech 4 can play: after every step the
// bodies pose the skeleton (poseSkeleton, through the bodies' joints and containedJoints), and
// each joint's parent-relative transform becomes one frame. Our own extension: the ragdoll's fall
// as an ordinary animation.
//
// Model space of the animation is the world (the entity at the origin); one frame per step, at
// the step rate rounded to whole frames per second.

#include "sim_scene.h"

#include "af/text/md5.h"

#include <string>
#include <vector>

namespace af::sim {

class Baker {
public:
    Baker(const Scene& scene, int figure);
    void addFrame(const World& world);
    // Writes through a temporary file renamed into place, so a failed write never leaves half a
    // file. Throws SceneError when it cannot.
    void write(const std::string& path) const;

private:
    const Scene& scene_;
    int figure_;
    std::vector<std::vector<Md5JointPose>> frames_;
    std::vector<Md5Bounds> bounds_;
};

}  // namespace af::sim
