#pragma once
// Loading our sample figures with their af_pose skeletons, for the figure tests.

#include "af/figure/figure.h"
#include "af/text/af_parser.h"
#include "af/text/md5.h"

#include <gtest/gtest.h>

#include <string>

namespace af::test {

inline std::string sourcePath(const std::string& relative) { return std::string(AF_SOURCE_DIR) + "/" + relative; }

inline Skeleton loadAfPose(const std::string& anim) {
    const Md5AnimParseResult r = loadMd5AnimFile(sourcePath(anim));
    EXPECT_TRUE(r.ok()) << r.diagnostics.formatAll();
    return skeletonFromMd5Anim(r.anim, 0);
}

inline DeclAF loadDecl(const std::string& af) {
    const AFParseResult r = loadAFFile(sourcePath(af));
    EXPECT_TRUE(r.ok()) << r.diagnostics.formatAll();
    return r.file.decls.at(0);
}

inline Skeleton humanoidPose() { return loadAfPose("models/humanoid/af_pose.md5anim"); }
inline DeclAF humanoidDecl() { return loadDecl("af/humanoid.af"); }

inline void expectNear(const Vec3& a, const Vec3& b, Real tolerance, const std::string& what) {
    EXPECT_LE((a - b).norm(), tolerance) << what << ": (" << a.transpose() << ") vs (" << b.transpose() << ")";
}

inline void expectNear(const Mat3& a, const Mat3& b, Real tolerance, const std::string& what) {
    EXPECT_LE((a - b).cwiseAbs().maxCoeff(), tolerance) << what << ":\n" << a << "\nvs\n" << b;
}

}  // namespace af::test
