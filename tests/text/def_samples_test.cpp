// The sample assets shipped with the library (def/*.def and the md5 files their model decls
// name) must load without errors, and the af_pose anim must fit its mesh.

#include "af/text/decl_def.h"
#include "af/text/md5.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace af {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> sampleDefFiles() {
    std::vector<fs::path> files;
    const fs::path dir = fs::path(AF_SOURCE_DIR) / "def";
    if (!fs::is_directory(dir)) return files;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir))
        if (entry.path().extension() == ".def") files.push_back(entry.path());
    std::sort(files.begin(), files.end());  // directory order is not deterministic
    return files;
}

TEST(DefSamples, SampleDefFilesAndTheirSkeletonsLoadWithoutErrors) {
    const std::vector<fs::path> files = sampleDefFiles();
    ASSERT_FALSE(files.empty()) << "no .def files in " << AF_SOURCE_DIR << "/def";

    DefCollection decls;
    std::vector<Diagnostic> merge;
    for (const fs::path& file : files) {
        const DefParseResult r = loadDefFile(file.string());
        EXPECT_TRUE(r.ok()) << r.diagnostics.formatAll();
        EXPECT_EQ(r.diagnostics.warningCount(), 0u) << r.diagnostics.formatAll();
        decls.add(r.file, merge);
    }
    EXPECT_TRUE(merge.empty());
    const ResolvedDefs resolved = resolveDefInheritance(decls);
    EXPECT_TRUE(resolved.ok()) << resolved.formatDiagnostics();
    ASSERT_FALSE(resolved.decls.models().empty());

    for (const EntityDef& def : resolved.decls.entityDefs()) {
        const DefKeyValue* model = def.find("model");
        if (!model) continue;
        EXPECT_NE(resolved.decls.findModel(model->value), nullptr)
            << "entityDef " << def.name << " names model " << model->value;
    }

    for (const ModelDecl& model : resolved.decls.models()) {
        SCOPED_TRACE("model " + model.name);
        ASSERT_FALSE(model.mesh.empty());
        const Md5MeshParseResult mesh = loadMd5MeshFile((fs::path(AF_SOURCE_DIR) / model.mesh).string());
        ASSERT_TRUE(mesh.ok()) << mesh.diagnostics.formatAll();

        const ModelAnim* pose = model.findAnim("af_pose");
        ASSERT_NE(pose, nullptr);
        const Md5AnimParseResult anim = loadMd5AnimFile((fs::path(AF_SOURCE_DIR) / pose->files.at(0)).string());
        ASSERT_TRUE(anim.ok()) << anim.diagnostics.formatAll();
        Diagnostics fit(pose->files[0]);
        checkMd5AnimMatchesMesh(anim.anim, mesh.mesh, fit);
        EXPECT_FALSE(fit.hasErrors()) << fit.formatAll();
        EXPECT_EQ(evaluateMd5AnimFrame(anim.anim, 0).size(), mesh.mesh.joints.size());
    }
}

}  // namespace
}  // namespace af
