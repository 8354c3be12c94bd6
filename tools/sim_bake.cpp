#include "sim_bake.h"

#include "af/text/atomic_write.h"
#include "af/text/md5_writer.h"

#include <cmath>
#include <limits>

namespace af::sim {

Baker::Baker(const Scene& scene, int figure) : scene_(scene), figure_(figure) {}

void Baker::addFrame(const World& world) {
    const FigureId id = scene_.figures[static_cast<std::size_t>(figure_)];
    const Figure& figure = world.definition(id);
    const std::vector<RigidPose> poses = world.bodyPoses(id);
    const Skeleton skeleton = world.skeleton(id);
    std::vector<Md5JointPose> frame;
    for (std::size_t j = 0; j < skeleton.size(); ++j) {
        const JointTransform local = skeleton.local(j);
        frame.push_back({{local.position.x(), local.position.y(), local.position.z()}, md5FromRotation(local.rotation)});
    }
    frames_.push_back(std::move(frame));

    Vec3 lo = Vec3::Constant(std::numeric_limits<Real>::infinity()), hi = -lo;
    for (std::size_t b = 0; b < poses.size(); ++b)
        for (const Vec3& v : figure.bodies[b].shape.vertices) {
            lo = lo.cwiseMin(poses[b].apply(v));
            hi = hi.cwiseMax(poses[b].apply(v));
        }
    bounds_.push_back({{lo.x(), lo.y(), lo.z()}, {hi.x(), hi.y(), hi.z()}});
}

void Baker::write(const std::string& path) const {
    if (frames_.empty()) throw SceneError("nothing to bake into " + path + ": the run took no step");
    const Figure& figure = scene_.world.definition(scene_.figures[static_cast<std::size_t>(figure_)]);
    const int frameRate = static_cast<int>(std::lround(1 / scene_.world.settings().timeStep));
    const Md5Anim anim = makeMd5Anim(figure.afPose.names, figure.afPose.parents, frames_, bounds_, frameRate,
                                     "af-sim: " + scene_.description);
    if (const WriteResult written = writeFileAtomically(path, writeMd5Anim(anim)); !written.ok())
        throw SceneError(written.error);
}

}  // namespace af::sim
