#pragma once
// Writing `.md5anim` files (docs/formats.md §2.2) that our reader and id Tech 4 read back, and
// building an Md5Anim from per-frame joint transforms.
//
// Quaternions follow md5.h: Doom's (conjugated) convention, unchanged. A file stores x, y, z
// only and the reader takes w = +sqrt(1 − x² − y² − z²), so a quaternion with w < 0 is written
// as its negation (the same rotation). Near w = 0 that recovery is limited by the file's float
// precision: w comes back within about 6e-8 / w of the written value.
//
// Numbers are written as the float values they stand for, each spelled so that it reads back as
// the same float (formatDeclFloat: ten decimals with trailing zeros removed, or the exponent form
// for magnitudes below about 1e-4, which Doom's lexer reads too). The components of a frame are
// written six to a line.

#include "af/text/md5.h"

#include <string>
#include <vector>

namespace af {

// The whole file. `anim` is written as it is: the root-translation rule of docs/formats.md §2.2
// is the reader's, so parseMd5Anim(writeMd5Anim(a)) holds a's values (rounded to float) and
// evaluates the same.
// Throws std::invalid_argument, and writes nothing, for an anim the reader would refuse: sizes
// that do not agree (bounds and frames per numFrames, baseframe per joint, components per frame),
// no frame or no joint, a negative frame rate, a hierarchy Doom does not accept (joint 0 a root,
// every other parent before its child, flags within 63, components inside the frame), a value
// that is not finite as a float, or a command line or joint name holding a `"` or a line break
// (md5 strings have no escapes).
std::string writeMd5Anim(const Md5Anim& anim);

// An animation of every component of every joint: flags 63, joint j's components at 6·j, in the
// order tx ty tz qx qy qz, so that evaluateMd5AnimFrame(result, f) gives frames[f] back.
//  * jointNames and parents describe the hierarchy (parents[0] = −1, then parents[j] < j);
//  * frames[f][j] is joint j's PARENT-RELATIVE translation (file units) and orientation (Doom's
//    quaternion, as md5.h) in frame f; the root's translation is its model-space position;
//  * bounds[f] is frame f's box in model space (one per frame, as the file wants).
// Values are rounded to float, as a file holds them. Each orientation is normalised and given
// w ≥ 0 (negated if needed), and its w recomputed from the rounded x, y, z, as the reader does, so
// that the result equals what reading its own file gives. The baseframe is frame 0, with the root
// translation 0: Doom makes the root's frame translations relative to the baseframe's and then
// sets that one to 0 (docs/formats.md §2.2), so a zero root baseframe keeps frame values as they
// are, and Doom's baseframe-only view of frame 0 (docs/formats.md §2.3) then differs from frame 0
// in the root translation only.
// Throws std::invalid_argument for sizes that do not agree, no joint or frame, a negative frame
// rate, a parent list the format does not allow, an orientation of zero or non-finite length, or
// anything writeMd5Anim would refuse.
Md5Anim makeMd5Anim(const std::vector<std::string>& jointNames, const std::vector<int>& parents,
                    const std::vector<std::vector<Md5JointPose>>& frames, const std::vector<Md5Bounds>& bounds,
                    int frameRate, std::string commandLine = {});

}  // namespace af
