#pragma once
// Reading `.md5mesh` skeletons and `.md5anim` animations (docs/formats.md §2.1, §2.2) into plain
// data, and evaluating one animation frame to parent-relative joint poses.
//
// Quaternion convention: every quaternion here is Doom's, exactly as the file writes it. Doom
// turns (x, y, z, w) into a matrix with the usual Hamilton formula but uses that matrix as a
// row-vector "axis", so the rotation it performs is the CONJUGATE of what v' = q v q^-1 gives.
// Anyone feeding these to a standard quaternion library must negate x, y, z (or w) first
// (docs/conventions.md §0.2). The text stage leaves them untouched; the figure stage converts them
// once.
//
// Numbers are held at float precision (each value is a float widened to af::Real), as Doom's
// lexer produces them. The md5 keywords are case-sensitive, as Doom's ExpectTokenString is.
// A malformed file gives one `file:line:col: error: ...` diagnostic and ok() == false; the
// data is then incomplete and must not be used.

#include "af/text/diagnostics.h"
#include "af/types.h"

#include <cmath>
#include <string>
#include <string_view>
#include <vector>

namespace af {

// A quaternion in Doom's (conjugated) convention; see the note at the top of this file.
struct Md5Quat {
    Real x = 0;
    Real y = 0;
    Real z = 0;
    Real w = 1;

    friend bool operator==(const Md5Quat&, const Md5Quat&) = default;
};

// md5 files store x, y, z only; w is non-negative. The absolute value guards against rounding
// that makes x² + y² + z² slightly exceed 1 (docs/formats.md §2.1; Doom's idCQuat::ToQuat does
// the same).
inline Real md5QuatW(Real x, Real y, Real z) { return std::sqrt(std::fabs(1 - (x * x + y * y + z * z))); }

inline Md5Quat md5QuatFromXyz(Real x, Real y, Real z) { return {x, y, z, md5QuatW(x, y, z)}; }

// ---- .md5mesh ------------------------------------------------------------------------------

// One joint of the bind pose, in MODEL space (not parent-relative).
struct Md5Joint {
    std::string name;
    int parent = -1;        // -1 for joint 0 only; otherwise smaller than the joint's own index
    Real3 position{};
    Md5Quat orientation;    // x, y, z as written, w reconstructed
    SourceLocation where;   // of the name
};

// What a mesh block held, for listings; the AF needs none of it.
struct Md5MeshSection {
    std::string name;       // the optional `name` key, usually empty
    std::string shader;
    int vertexCount = 0;
    int triangleCount = 0;
    int weightCount = 0;
};

struct Md5Mesh {
    std::string commandLine;
    std::vector<Md5Joint> joints;
    std::vector<Md5MeshSection> meshes;

    // The index of a joint by name, ignoring case (as all AF code matches joints), or -1.
    int findJoint(std::string_view name) const;
};

struct Md5MeshParseResult {
    Md5Mesh mesh;
    Diagnostics diagnostics;

    bool ok() const { return !diagnostics.hasErrors(); }
};

// Parses `text`; `fileName` is used in diagnostics only.
Md5MeshParseResult parseMd5Mesh(std::string_view text, std::string fileName);
// Reads and parses a file; a file that cannot be read is an error diagnostic.
Md5MeshParseResult loadMd5MeshFile(const std::string& path);

// ---- .md5anim ------------------------------------------------------------------------------

// Which components of a joint a frame animates. A joint's animated values sit in this bit order
// from `firstComponent` on inside each frame's component array.
namespace md5anim {
constexpr unsigned Tx = 1, Ty = 2, Tz = 4, Qx = 8, Qy = 16, Qz = 32;
constexpr unsigned AllBits = 63;
}  // namespace md5anim

struct Md5AnimJoint {
    std::string name;
    int parent = -1;
    unsigned flags = 0;      // md5anim::Tx ... md5anim::Qz
    int firstComponent = 0;
    SourceLocation where;    // of the name
};

struct Md5Bounds {
    Real3 min{};
    Real3 max{};
};

// A parent-relative joint transform: baseframe entries and evaluated frames.
struct Md5JointPose {
    Real3 translation{};
    Md5Quat orientation;
};

// The file as written. The root-translation rule of docs/formats.md §2.2 is NOT applied to this
// data (so it can be written back unchanged); evaluateMd5AnimFrame applies it.
struct Md5Anim {
    std::string commandLine;
    int frameCount = 0;
    int frameRate = 0;
    int animatedComponentCount = 0;
    std::vector<Md5AnimJoint> joints;
    std::vector<Md5Bounds> bounds;           // one per frame
    std::vector<Md5JointPose> baseFrame;     // one per joint, w reconstructed
    std::vector<Real> components;            // frameCount × animatedComponentCount, frame-major
    SourceLocation numJointsWhere;           // of the numJoints value, for mesh mismatches

    // The animated components of one frame (animatedComponentCount values).
    const Real* frameComponents(int frame) const {
        return components.data() + static_cast<std::size_t>(frame) * static_cast<std::size_t>(animatedComponentCount);
    }
};

struct Md5AnimParseResult {
    Md5Anim anim;
    Diagnostics diagnostics;

    bool ok() const { return !diagnostics.hasErrors(); }
};

Md5AnimParseResult parseMd5Anim(std::string_view text, std::string fileName);
Md5AnimParseResult loadMd5AnimFile(const std::string& path);

// Frame `frame` (0-based) as parent-relative poses, one per joint, by Doom's rules:
//  * each joint starts from its baseframe entry; its animated components override it;
//  * w is recomputed from x, y, z only when at least one quaternion component is animated,
//    otherwise the baseframe quaternion (with its w) is kept whole;
//  * the root (joint 0) translation is relative to the baseframe: animated root axes give
//    "frame value − baseframe value" (rounded to float, as Doom stores it), other root axes 0.
// Frame 0 includes its components, unlike Doom's GetSingleFrame(0), which returns the baseframe
// (docs/formats.md §2.3: we use frame 0 for the AF pose). Conversion to model space and the
// quaternion conjugation are the figure stage's job. Throws std::out_of_range for a frame outside
// [0, frameCount) and std::invalid_argument for an anim whose sizes do not agree (one that did
// not parse cleanly).
std::vector<Md5JointPose> evaluateMd5AnimFrame(const Md5Anim& anim, int frame);

// Doom's check that an anim fits a mesh (idMD5Anim::CheckModelHierarchy): the same joint count,
// names (case-sensitive, as Doom compares them) and parents, joint by joint. Problems are
// reported as errors in `animDiagnostics`, at the anim's positions.
void checkMd5AnimMatchesMesh(const Md5Anim& anim, const Md5Mesh& mesh, Diagnostics& animDiagnostics);

}  // namespace af
