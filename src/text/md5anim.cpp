// `.md5anim` files (docs/formats.md §2.2) and the evaluation of one frame.

#include "af/text/md5.h"
#include "md5_common.h"

#include <bit>
#include <stdexcept>

namespace af {

using namespace md5detail;

namespace {

std::string quoted(int value) { return "'" + std::to_string(value) + "'"; }

class Md5AnimParser {
public:
    Md5AnimParser(std::string_view text, Diagnostics& diagnostics) : in_(text, diagnostics) {}

    void parse(Md5Anim& anim) {
        anim.commandLine = readHeader(in_);
        anim.frameCount = readCount(in_, "numFrames", 1);
        expectKeyword(in_, "numJoints");
        anim.numJointsWhere = in_.peek().where;
        const int jointCount = in_.readInt("numJoints");
        if (jointCount <= 0)
            failAt(in_, anim.numJointsWhere, "expected numJoints greater than 0, found " + quoted(jointCount));
        anim.frameRate = readCount(in_, "frameRate", 0);
        expectKeyword(in_, "numAnimatedComponents");
        SourceLocation where;
        const int componentCount = in_.readInt("numAnimatedComponents", &where);
        if (componentCount < 0 || componentCount > 6 * jointCount)
            failAt(in_, where, "expected numAnimatedComponents from 0 to " + std::to_string(6 * jointCount) +
                                   " (6 per joint), found " + quoted(componentCount));
        anim.animatedComponentCount = componentCount;

        parseHierarchy(anim, jointCount);

        expectKeyword(in_, "bounds");
        in_.expectPunctuation("{", "after bounds");
        for (int i = 0; i < anim.frameCount; ++i) {
            Md5Bounds b;
            b.min = readTuple3(in_, "the minimum of the bounds of frame " + std::to_string(i));
            b.max = readTuple3(in_, "the maximum of the bounds of frame " + std::to_string(i));
            anim.bounds.push_back(b);
        }
        in_.expectPunctuation("}", "after the bounds of " + std::to_string(anim.frameCount) + " frames (numFrames)");

        expectKeyword(in_, "baseframe");
        in_.expectPunctuation("{", "after baseframe");
        for (int i = 0; i < jointCount; ++i) {
            Md5JointPose pose;
            pose.translation = readTuple3(in_, "the baseframe translation of joint " + std::to_string(i));
            pose.orientation = readQuat(in_, "the baseframe orientation of joint " + std::to_string(i));
            anim.baseFrame.push_back(pose);
        }
        in_.expectPunctuation("}", "after the baseframe of " + std::to_string(jointCount) + " joints (numJoints)");

        anim.components.reserve(static_cast<std::size_t>(anim.frameCount) * static_cast<std::size_t>(componentCount));
        for (int i = 0; i < anim.frameCount; ++i) parseFrame(anim, i);
        expectEnd(in_, "the " + std::to_string(anim.frameCount) + " frames (numFrames)");
    }

private:
    void parseHierarchy(Md5Anim& anim, int jointCount) {
        const int componentCount = anim.animatedComponentCount;
        expectKeyword(in_, "hierarchy");
        in_.expectPunctuation("{", "after hierarchy");
        for (int i = 0; i < jointCount; ++i) {
            Md5AnimJoint joint;
            const Token name = readWord(in_, "the name of joint " + std::to_string(i + 1) + " of " +
                                                 std::to_string(jointCount) + " (numJoints)");
            joint.name = name.text;
            joint.where = name.where;

            SourceLocation where;
            joint.parent = in_.readInt("the parent index", &where);
            if (i == 0 && joint.parent != -1)
                failAt(in_, where, "expected parent -1 for the first joint (the root), found " + quoted(joint.parent));
            if (i > 0 && (joint.parent < 0 || joint.parent >= i))
                failAt(in_, where, "expected a parent index from 0 to " + std::to_string(i - 1) +
                                       " (only the first joint is a root; a parent comes before its children), found " +
                                       quoted(joint.parent));

            const int flags = in_.readInt("the animated-component flags", &where);
            if (flags < 0 || (static_cast<unsigned>(flags) & ~md5anim::AllBits) != 0)
                failAt(in_, where, "expected flags from 0 to 63 (1 Tx, 2 Ty, 4 Tz, 8 Qx, 16 Qy, 32 Qz), found " +
                                       quoted(flags));
            joint.flags = static_cast<unsigned>(flags);

            joint.firstComponent = in_.readInt("the first component index", &where);
            // A joint that animates nothing never reads its index; exporters write the running
            // count there, which may be one past the last component. Doom 3 rejects that case; we
            // accept it because the index is never used.
            const int used = std::popcount(joint.flags);
            const int last = used == 0 ? componentCount : componentCount - used;
            if (joint.firstComponent < 0 || joint.firstComponent > last) {
                failAt(in_, where, "expected a first component index from 0 to " + std::to_string(last) +
                                       " (numAnimatedComponents " + std::to_string(componentCount) +
                                       ", this joint animates " + std::to_string(used) + "), found " +
                                       quoted(joint.firstComponent));
            }
            anim.joints.push_back(std::move(joint));
        }
        in_.expectPunctuation("}", "after the " + std::to_string(jointCount) + " joints of the hierarchy (numJoints)");
    }

    void parseFrame(Md5Anim& anim, int index) {
        const int componentCount = anim.animatedComponentCount;
        const std::string ordinal = std::to_string(index) + " of " + std::to_string(anim.frameCount) + " (numFrames)";
        expectKeyword(in_, "frame", ordinal);
        SourceLocation where;
        const int number = in_.readInt("the frame number", &where);
        if (number != index)
            failAt(in_, where, "expected frame number " + std::to_string(index) + " (frames count up from 0), found " +
                                   quoted(number));
        in_.expectPunctuation("{", "after frame " + std::to_string(index));
        for (int k = 0; k < componentCount; ++k) {
            anim.components.push_back(in_.readFloat("component " + std::to_string(k) + " of frame " +
                                                    std::to_string(index) + " (numAnimatedComponents " +
                                                    std::to_string(componentCount) + ")"));
        }
        in_.expectPunctuation("}", "after the " + std::to_string(componentCount) + " components of frame " +
                                       std::to_string(index) + " (numAnimatedComponents)");
    }

    TokenReader in_;
};

}  // namespace

Md5AnimParseResult parseMd5Anim(std::string_view text, std::string fileName) {
    Md5AnimParseResult result{{}, Diagnostics(std::move(fileName))};
    Md5AnimParser parser(text, result.diagnostics);
    try {
        parser.parse(result.anim);
    } catch (const ParseAbort&) {
    }
    return result;
}

Md5AnimParseResult loadMd5AnimFile(const std::string& path) {
    if (std::optional<std::string> text = readWholeFile(path)) return parseMd5Anim(*text, path);
    Md5AnimParseResult result{{}, Diagnostics(path)};
    result.diagnostics.error({}, "cannot open the file for reading");
    return result;
}

std::vector<Md5JointPose> evaluateMd5AnimFrame(const Md5Anim& anim, int frame) {
    if (frame < 0 || frame >= anim.frameCount)
        throw std::out_of_range("md5anim frame " + std::to_string(frame) + " is outside [0, " +
                                std::to_string(anim.frameCount) + ")");
    const std::size_t componentCount = static_cast<std::size_t>(anim.animatedComponentCount);
    if (anim.baseFrame.size() != anim.joints.size() || anim.joints.empty() ||
        anim.components.size() != static_cast<std::size_t>(anim.frameCount) * componentCount)
        throw std::invalid_argument("md5anim data is incomplete (it did not parse cleanly)");

    std::vector<Md5JointPose> poses = anim.baseFrame;
    poses[0].translation = {0, 0, 0};
    const Real* values = anim.frameComponents(frame);
    for (std::size_t j = 0; j < anim.joints.size(); ++j) {
        const Md5AnimJoint& info = anim.joints[j];
        if (info.flags == 0) continue;
        std::size_t k = static_cast<std::size_t>(info.firstComponent);
        if (info.firstComponent < 0 || k + static_cast<std::size_t>(std::popcount(info.flags)) > componentCount)
            throw std::invalid_argument("md5anim joint " + std::to_string(j) + " reads past its frame's components");
        Md5JointPose& pose = poses[j];
        for (int axis = 0; axis < 3; ++axis) {
            if ((info.flags & (md5anim::Tx << axis)) == 0) continue;
            const Real value = values[k++];
            // Doom subtracts in float on load, so the result is rounded to float.
            pose.translation[axis] =
                j == 0 ? Real(static_cast<float>(value - anim.baseFrame[0].translation[axis])) : value;
        }
        Real* xyz[3] = {&pose.orientation.x, &pose.orientation.y, &pose.orientation.z};
        bool rotated = false;
        for (int axis = 0; axis < 3; ++axis) {
            if ((info.flags & (md5anim::Qx << axis)) == 0) continue;
            *xyz[axis] = values[k++];
            rotated = true;
        }
        if (rotated) pose.orientation.w = md5QuatW(pose.orientation.x, pose.orientation.y, pose.orientation.z);
    }
    return poses;
}

void checkMd5AnimMatchesMesh(const Md5Anim& anim, const Md5Mesh& mesh, Diagnostics& animDiagnostics) {
    if (anim.joints.size() != mesh.joints.size()) {
        animDiagnostics.error(anim.numJointsWhere, "expected numJoints " + std::to_string(mesh.joints.size()) +
                                                       " as in the mesh, found " + quoted(int(anim.joints.size())));
        return;
    }
    for (std::size_t i = 0; i < anim.joints.size(); ++i) {
        const Md5AnimJoint& a = anim.joints[i];
        const Md5Joint& m = mesh.joints[i];
        if (a.name != m.name)
            animDiagnostics.error(a.where, "expected joint " + std::to_string(i) + " to be named \"" + m.name +
                                               "\" as in the mesh, found \"" + a.name + "\"");
        else if (a.parent != m.parent)
            animDiagnostics.error(a.where, "expected parent " + std::to_string(m.parent) + " for joint \"" + a.name +
                                               "\" as in the mesh, found " + quoted(a.parent));
    }
}

}  // namespace af
