#pragma once
// The benchmarks' figure: our humanoid (af/humanoid.af at its af_pose) hung from the world by
// its chest with a fixed joint, as issue #4 asks for.

#include "af/figure/figure.h"
#include "af/text/af_parser.h"
#include "af/text/md5.h"

#include <string>

namespace af::bench {

// The decl with its chest welded to the world (a fixed joint "hang"); the tests hang it too.
inline DeclAF hungByTheChest(DeclAF decl) {
    AFConstraint hang;
    hang.type = ConstraintType::Fixed;
    hang.name = "hang";
    hang.body1 = "chest";
    hang.body2 = "world";
    decl.constraints.push_back(hang);
    return decl;
}

inline Figure hungHumanoid() {
    const std::string root = AF_SOURCE_DIR;
    AFParseResult parsed = loadAFFile(root + "/af/humanoid.af");
    const Md5AnimParseResult anim = loadMd5AnimFile(root + "/models/humanoid/af_pose.md5anim");
    return *buildFigure(hungByTheChest(parsed.file.decls.at(0)), skeletonFromMd5Anim(anim.anim, 0), "humanoid.af").figure;
}

}  // namespace af::bench
