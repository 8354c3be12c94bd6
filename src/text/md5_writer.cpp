// `.md5anim` writing, in the layout of id's exporter, and building an anim from joint transforms.

#include "af/text/md5_writer.h"

#include "text_writer.h"

#include <bit>
#include <cmath>
#include <stdexcept>

namespace af {

namespace {

[[noreturn]] void refuse(const std::string& what) { throw std::invalid_argument("md5anim: " + what); }

void checkString(const std::string& s, const std::string& what) {
    if (s.find_first_of("\"\n\r") != std::string::npos)
        refuse(what + " holds a '\"' or a line break, which an md5 string cannot");
}

void checkFinite(Real v, const std::string& what) {
    if (!std::isfinite(static_cast<float>(v))) refuse(what + " is not a finite float");
}

void checkFinite(const Real3& v, const std::string& what) {
    for (Real x : v) checkFinite(x, what);
}

// Everything the reader checks, so that a file we write always reads back.
void checkWritable(const Md5Anim& a) {
    checkString(a.commandLine, "the command line");
    const std::size_t jointCount = a.joints.size();
    if (a.frameCount <= 0) refuse("numFrames must be greater than 0");
    if (jointCount == 0) refuse("numJoints must be greater than 0");
    if (a.frameRate < 0) refuse("frameRate must be 0 or more");
    const int componentCount = a.animatedComponentCount;
    if (componentCount < 0 || static_cast<std::size_t>(componentCount) > 6 * jointCount)
        refuse("numAnimatedComponents must be from 0 to 6 per joint");
    if (a.bounds.size() != static_cast<std::size_t>(a.frameCount)) refuse("there must be one bounds box per frame");
    if (a.baseFrame.size() != jointCount) refuse("there must be one baseframe entry per joint");
    if (a.components.size() != static_cast<std::size_t>(a.frameCount) * static_cast<std::size_t>(componentCount))
        refuse("there must be numAnimatedComponents values per frame");

    for (std::size_t i = 0; i < jointCount; ++i) {
        const Md5AnimJoint& j = a.joints[i];
        const std::string name = "joint " + std::to_string(i);
        checkString(j.name, "the name of " + name);
        if (i == 0 ? j.parent != -1 : (j.parent < 0 || static_cast<std::size_t>(j.parent) >= i))
            refuse("the parent of " + name + " must be " + (i == 0 ? "-1" : "an earlier joint"));
        if ((j.flags & ~md5anim::AllBits) != 0) refuse("the flags of " + name + " must be within 63");
        const int used = std::popcount(j.flags);
        if (j.firstComponent < 0 || j.firstComponent > componentCount - used)
            refuse("the components of " + name + " lie outside the frame's");
        checkFinite(a.baseFrame[i].translation, "the baseframe translation of " + name);
        checkFinite({a.baseFrame[i].orientation.x, a.baseFrame[i].orientation.y, a.baseFrame[i].orientation.z},
                    "the baseframe orientation of " + name);
    }
    for (const Md5Bounds& b : a.bounds) {
        checkFinite(b.min, "a bounds box");
        checkFinite(b.max, "a bounds box");
    }
    for (Real v : a.components) checkFinite(v, "a frame component");
}

class Md5Writer : public text_detail::TextWriter<Md5Writer> {
public:
    Md5Writer& tuple(Real x, Real y, Real z) { return raw("( ").num(x).raw(" ").num(y).raw(" ").num(z).raw(" )"); }
    Md5Writer& tuple(const Real3& v) { return tuple(v[0], v[1], v[2]); }

    void header(const Md5Anim& a) {
        raw("MD5Version 10\ncommandline ").quoted(a.commandLine).raw("\n\n");
        raw("numFrames ").integer(a.frameCount).raw("\n");
        raw("numJoints ").integer(static_cast<int>(a.joints.size())).raw("\n");
        raw("frameRate ").integer(a.frameRate).raw("\n");
        raw("numAnimatedComponents ").integer(a.animatedComponentCount).raw("\n\n");
    }

    // The exporter's trailing comment names the parent and the animated components.
    void hierarchy(const Md5Anim& a) {
        static constexpr const char* kComponentNames[] = {"Tx", "Ty", "Tz", "Qx", "Qy", "Qz"};
        raw("hierarchy {\n");
        for (const Md5AnimJoint& j : a.joints) {
            raw("\t").quoted(j.name).raw("\t").integer(j.parent).raw(" ").integer(static_cast<int>(j.flags));
            raw(" ").integer(j.firstComponent);
            if (j.parent >= 0 || j.flags != 0) {
                raw("\t//");
                if (j.parent >= 0) raw(" ").raw(a.joints[static_cast<std::size_t>(j.parent)].name);
                if (j.flags != 0) {
                    raw(" (");
                    for (unsigned bit = 0; bit < 6; ++bit)
                        if ((j.flags & (1u << bit)) != 0) raw(" ").raw(kComponentNames[bit]);
                    raw(" )");
                }
            }
            raw("\n");
        }
        raw("}\n\n");
    }

    void bounds(const Md5Anim& a) {
        raw("bounds {\n");
        for (const Md5Bounds& b : a.bounds) raw("\t").tuple(b.min).raw(" ").tuple(b.max).raw("\n");
        raw("}\n\n");
    }

    void baseFrame(const Md5Anim& a) {
        raw("baseframe {\n");
        for (const Md5JointPose& p : a.baseFrame) {
            // The reader recovers w >= 0; -q is the same rotation with that sign.
            const Md5Quat& q = p.orientation;
            const Real s = q.w < 0 ? -1 : 1;
            raw("\t").tuple(p.translation).raw(" ").tuple(s * q.x, s * q.y, s * q.z).raw("\n");
        }
        raw("}\n\n");
    }

    void frames(const Md5Anim& a) {
        const int perLine = 6;
        for (int f = 0; f < a.frameCount; ++f) {
            raw("frame ").integer(f).raw(" {\n");
            const Real* values = a.frameComponents(f);
            for (int k = 0; k < a.animatedComponentCount; ++k) {
                raw(k % perLine == 0 ? "\t" : " ").num(values[k]);
                if (k % perLine == perLine - 1 || k == a.animatedComponentCount - 1) raw("\n");
            }
            raw("}\n\n");
        }
    }
};

// Through a volatile because GCC 12.2's SLP vectorizer (on at -O2) drops the rounding of a
// (double)(float) round trip done on two neighbouring values: {(double)(float)p.x,
// (double)(float)p.y} comes out unrounded.
Real toFloat(Real v) {
    volatile float f = static_cast<float>(v);
    return f;
}

Real3 toFloat(const Real3& v) { return {toFloat(v[0]), toFloat(v[1]), toFloat(v[2])}; }

// Unit length, w >= 0, x, y, z rounded to float and w recovered from them as the reader does.
Md5Quat fileQuat(const Md5Quat& q, const std::string& what) {
    const Real length = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
    if (!std::isfinite(length) || length == 0) refuse(what + " is not a rotation (length " + std::to_string(length) + ")");
    const Real s = (q.w < 0 ? -1 : 1) / length;
    return md5QuatFromXyz(toFloat(s * q.x), toFloat(s * q.y), toFloat(s * q.z));
}

}  // namespace

std::string writeMd5Anim(const Md5Anim& anim) {
    checkWritable(anim);
    Md5Writer w;
    w.header(anim);
    w.hierarchy(anim);
    w.bounds(anim);
    w.baseFrame(anim);
    w.frames(anim);
    return w.take();
}

Md5Anim makeMd5Anim(const std::vector<std::string>& jointNames, const std::vector<int>& parents,
                    const std::vector<std::vector<Md5JointPose>>& frames, const std::vector<Md5Bounds>& bounds,
                    int frameRate, std::string commandLine) {
    const std::size_t jointCount = jointNames.size();
    if (jointCount == 0 || frames.empty()) refuse("an anim needs a joint and a frame");
    if (parents.size() != jointCount) refuse("there must be one parent per joint name");
    if (bounds.size() != frames.size()) refuse("there must be one bounds box per frame");

    Md5Anim a;
    a.commandLine = std::move(commandLine);
    a.frameCount = static_cast<int>(frames.size());
    a.frameRate = frameRate;
    a.animatedComponentCount = static_cast<int>(6 * jointCount);
    for (std::size_t j = 0; j < jointCount; ++j)
        a.joints.push_back({jointNames[j], parents[j], md5anim::AllBits, static_cast<int>(6 * j), {}});
    for (const Md5Bounds& b : bounds) a.bounds.push_back({toFloat(b.min), toFloat(b.max)});

    a.components.reserve(frames.size() * 6 * jointCount);
    for (std::size_t f = 0; f < frames.size(); ++f) {
        if (frames[f].size() != jointCount)
            refuse("frame " + std::to_string(f) + " has " + std::to_string(frames[f].size()) + " joints, not " +
                   std::to_string(jointCount));
        for (std::size_t j = 0; j < jointCount; ++j) {
            const Md5JointPose& p = frames[f][j];
            const Md5Quat q =
                fileQuat(p.orientation, "the orientation of joint " + std::to_string(j) + " in frame " + std::to_string(f));
            const Real3 t = toFloat(p.translation);
            a.components.insert(a.components.end(), {t[0], t[1], t[2], q.x, q.y, q.z});
            if (f == 0) a.baseFrame.push_back({j == 0 ? Real3{} : t, q});
        }
    }
    checkWritable(a);
    return a;
}

}  // namespace af
