// .md5mesh reader: the bind-pose skeleton, w reconstruction, structural checks of the mesh
// blocks, and one positioned diagnostic for each kind of malformed file.

#include "af/text/md5.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace af {
namespace {

// Line numbers below refer to this text (line 1 is "MD5Version 10").
const std::string kMesh =
    "MD5Version 10\n"                                     // 1
    "commandline \"exported by hand\"\n"                  // 2
    "\n"                                                  // 3
    "numJoints 3\n"                                       // 4
    "numMeshes 1\n"                                       // 5
    "\n"                                                  // 6
    "joints {\n"                                          // 7
    "\t\"origin\"\t-1 ( 0 0 0 ) ( 0 0 0 )\n"              // 8
    "\t\"Hips\"\t0 ( 1 -2 40.5 ) ( 0.5 0.5 0.5 )\t\t// origin\n"  // 9
    "\t\"Spine\"\t1 ( 0 0 50 ) ( 0 0 -0.6 )\n"            // 10
    "}\n"                                                 // 11
    "\n"                                                  // 12
    "mesh {\n"                                            // 13
    "\tshader \"models/skin\"\n"                          // 14
    "\tnumverts 3\n"                                      // 15
    "\tvert 0 ( 0 0 ) 0 1\n"                              // 16
    "\tvert 1 ( 1 0 ) 1 1\n"                              // 17
    "\tvert 2 ( 0 1 ) 2 1\n"                              // 18
    "\tnumtris 1\n"                                       // 19
    "\ttri 0 0 1 2\n"                                     // 20
    "\tnumweights 3\n"                                    // 21
    "\tweight 0 0 1 ( 0 0 0 )\n"                          // 22
    "\tweight 1 1 1 ( 1 0 0 )\n"                          // 23
    "\tweight 2 2 1 ( 0 1 0 )\n"                          // 24
    "}\n";                                                // 25

// kMesh with the first occurrence of `from` replaced by `to`.
std::string meshWith(const std::string& from, const std::string& to) {
    std::string text = kMesh;
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

// The only diagnostic of a text that must not load.
std::string onlyMeshError(const std::string& text) {
    const Md5MeshParseResult r = parseMd5Mesh(text, "bad.md5mesh");
    EXPECT_FALSE(r.ok());
    EXPECT_EQ(r.diagnostics.all().size(), 1u) << r.diagnostics.formatAll();
    return r.diagnostics.all().empty() ? std::string() : r.diagnostics.all().front().format();
}

TEST(Md5Mesh, KeepsModelSpaceJointsAsWritten) {
    const Md5MeshParseResult r = parseMd5Mesh(kMesh, "test.md5mesh");
    ASSERT_TRUE(r.ok()) << r.diagnostics.formatAll();
    const Md5Mesh& mesh = r.mesh;
    EXPECT_EQ(mesh.commandLine, "exported by hand");
    ASSERT_EQ(mesh.joints.size(), 3u);
    EXPECT_EQ(mesh.joints[0].name, "origin");
    EXPECT_EQ(mesh.joints[0].parent, -1);
    EXPECT_EQ(mesh.joints[1].name, "Hips");
    EXPECT_EQ(mesh.joints[1].parent, 0);
    EXPECT_EQ(mesh.joints[1].position, (Real3{1, -2, 40.5}));
    EXPECT_EQ(mesh.joints[1].where, (SourceLocation{9, 2}));
    EXPECT_EQ(mesh.joints[2].parent, 1);
    ASSERT_EQ(mesh.meshes.size(), 1u);
    EXPECT_EQ(mesh.meshes[0].shader, "models/skin");
    EXPECT_EQ(mesh.meshes[0].vertexCount, 3);
    EXPECT_EQ(mesh.meshes[0].triangleCount, 1);
    EXPECT_EQ(mesh.meshes[0].weightCount, 3);
}

TEST(Md5Mesh, ReconstructsNonNegativeW) {
    const Md5MeshParseResult r = parseMd5Mesh(kMesh, "test.md5mesh");
    ASSERT_TRUE(r.ok()) << r.diagnostics.formatAll();
    EXPECT_EQ(r.mesh.joints[0].orientation, (Md5Quat{0, 0, 0, 1}));
    EXPECT_EQ(r.mesh.joints[1].orientation, (Md5Quat{0.5, 0.5, 0.5, 0.5}));
    // z is -0.6 at float precision; w = sqrt(1 - 0.36) = 0.8, and positive although z is negative.
    const Md5Quat q = r.mesh.joints[2].orientation;
    EXPECT_EQ(q.z, Real(-0.6f));
    EXPECT_NEAR(q.w, 0.8, 1e-7);
}

TEST(Md5Mesh, QuatWUsesAbsoluteValueWhenXyzIsLongerThanOne) {
    // Rounding can push x²+y²+z² past 1; Doom takes |1 - x²-y²-z²| instead of failing.
    EXPECT_DOUBLE_EQ(md5QuatW(0.6, 0.6, 0.6), std::sqrt(0.08));
    EXPECT_DOUBLE_EQ(md5QuatW(0, 0, 0), 1.0);
    EXPECT_DOUBLE_EQ(md5QuatW(1, 0, 0), 0.0);
}

TEST(Md5Mesh, FindJointIgnoresCase) {
    const Md5MeshParseResult r = parseMd5Mesh(kMesh, "test.md5mesh");
    EXPECT_EQ(r.mesh.findJoint("hips"), 1);
    EXPECT_EQ(r.mesh.findJoint("SPINE"), 2);
    EXPECT_EQ(r.mesh.findJoint("tail"), -1);
}

TEST(Md5Mesh, AcceptsOptionalMeshNameAndZeroMeshes) {
    const Md5MeshParseResult named = parseMd5Mesh(meshWith("\tshader", "\tname \"body\"\n\tshader"), "t.md5mesh");
    ASSERT_TRUE(named.ok()) << named.diagnostics.formatAll();
    EXPECT_EQ(named.mesh.meshes[0].name, "body");

    std::string skeletonOnly = kMesh.substr(0, kMesh.find("mesh {"));
    skeletonOnly.replace(skeletonOnly.find("numMeshes 1"), 11, "numMeshes 0");
    const Md5MeshParseResult bare = parseMd5Mesh(skeletonOnly, "t.md5mesh");
    EXPECT_TRUE(bare.ok()) << bare.diagnostics.formatAll();
    EXPECT_TRUE(bare.mesh.meshes.empty());
}

TEST(Md5Mesh, RejectsOtherVersions) {
    EXPECT_EQ(onlyMeshError(meshWith("MD5Version 10", "MD5Version 11")),
              "bad.md5mesh:1:12: error: expected MD5Version 10, found '11'");
}

TEST(Md5Mesh, KeywordsAreCaseSensitiveAsInDoom) {
    EXPECT_EQ(onlyMeshError(meshWith("numJoints", "numjoints")),
              "bad.md5mesh:4:1: error: expected 'numJoints', found 'numjoints'");
}

TEST(Md5Mesh, RejectsParentThatDoesNotPrecedeItsChild) {
    EXPECT_EQ(onlyMeshError(meshWith("\"Spine\"\t1", "\"Spine\"\t2")),
              "bad.md5mesh:10:10: error: expected a parent index from 0 to 1 (a parent comes before its children), "
              "found '2'");
}

TEST(Md5Mesh, RejectsSecondRoot) {
    EXPECT_EQ(onlyMeshError(meshWith("\"Spine\"\t1", "\"Spine\"\t-1")),
              "bad.md5mesh:10:10: error: expected a parent index from 0 to 1 (a parent comes before its children), "
              "found '-1'");
}

TEST(Md5Mesh, RejectsFirstJointWithParent) {
    EXPECT_EQ(onlyMeshError(meshWith("\"origin\"\t-1", "\"origin\"\t0")),
              "bad.md5mesh:8:11: error: expected parent -1 for the first joint (the root), found '0'");
}

TEST(Md5Mesh, RejectsFewerJointsThanNumJoints) {
    EXPECT_EQ(onlyMeshError(meshWith("numJoints 3", "numJoints 4")),
              "bad.md5mesh:11:1: error: expected the name of joint 4 of 4 (numJoints), found '}'");
}

TEST(Md5Mesh, RejectsMoreJointsThanNumJoints) {
    EXPECT_EQ(onlyMeshError(meshWith("numJoints 3", "numJoints 2")),
              "bad.md5mesh:10:2: error: expected '}' after the 2 joints (numJoints), found \"Spine\"");
}

TEST(Md5Mesh, RejectsJointNamesThatDifferOnlyInCase) {
    EXPECT_EQ(onlyMeshError(meshWith("\"Spine\"", "\"hips\"")),
              "bad.md5mesh:10:2: error: expected a unique joint name, found \"hips\" (joint 1 at line 9 has the "
              "same name, ignoring case)");
}

TEST(Md5Mesh, RejectsWeightOnJointThatDoesNotExist) {
    EXPECT_EQ(onlyMeshError(meshWith("weight 2 2 1", "weight 2 3 1")),
              "bad.md5mesh:24:11: error: expected a joint index from 0 to 2, found '3'");
}

TEST(Md5Mesh, RejectsVertexWithoutWeights) {
    EXPECT_EQ(onlyMeshError(meshWith("vert 1 ( 1 0 ) 1 1", "vert 1 ( 1 0 ) 1 0")),
              "bad.md5mesh:17:19: error: expected a weight count greater than 0, found '0'");
}

TEST(Md5Mesh, RejectsVerticesThatUseMoreWeightsThanDeclared) {
    EXPECT_EQ(onlyMeshError(meshWith("vert 2 ( 0 1 ) 2 1", "vert 2 ( 0 1 ) 2 2")),
              "bad.md5mesh:21:13: error: expected numweights of at least 4 (the vertices use that many), found '3'");
}

TEST(Md5Mesh, RejectsTriangleOnVertexThatDoesNotExist) {
    EXPECT_EQ(onlyMeshError(meshWith("tri 0 0 1 2", "tri 0 0 1 3")),
              "bad.md5mesh:20:12: error: expected a vertex index from 0 to 2, found '3'");
}

TEST(Md5Mesh, RejectsFewerMeshesThanNumMeshes) {
    EXPECT_EQ(onlyMeshError(meshWith("numMeshes 1", "numMeshes 2")),
              "bad.md5mesh:26:1: error: expected 'mesh' 2 of 2 (numMeshes), found end of file");
}

TEST(Md5Mesh, RejectsMoreVertsThanNumverts) {
    EXPECT_EQ(onlyMeshError(meshWith("numverts 3", "numverts 2")),
              "bad.md5mesh:18:2: error: expected 'numtris', found 'vert'");
}

TEST(Md5Mesh, RejectsCommasInsideTuples) {
    // Parse1DMatrix takes no commas; a comma is the classic hand-editing mistake.
    EXPECT_EQ(onlyMeshError(meshWith("( 1 -2 40.5 )", "( 1, -2, 40.5 )")),
              "bad.md5mesh:9:14: error: expected a number for the joint position, found ','");
}

TEST(Md5Mesh, EveryTruncationIsOneErrorNeverACrash) {
    const std::size_t complete = kMesh.rfind('}');
    for (std::size_t n = 0; n <= complete; ++n) {
        const Md5MeshParseResult r = parseMd5Mesh(kMesh.substr(0, n), "cut.md5mesh");
        EXPECT_FALSE(r.ok()) << "cut at " << n;
        EXPECT_EQ(r.diagnostics.errorCount(), 1u) << "cut at " << n << "\n" << r.diagnostics.formatAll();
    }
}

TEST(Md5Mesh, MissingFileIsAnError) {
    const Md5MeshParseResult r = loadMd5MeshFile("/nonexistent/x.md5mesh");
    EXPECT_FALSE(r.ok());
    EXPECT_EQ(r.diagnostics.formatAll(), "/nonexistent/x.md5mesh: error: cannot open the file for reading\n");
}

}  // namespace
}  // namespace af
