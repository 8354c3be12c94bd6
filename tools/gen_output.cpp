// af-gen's files and report (gen_output.h).

#include "gen_output.h"

#include "af/text/af_writer.h"
#include "af/text/atomic_write.h"
#include "af/text/md5_writer.h"

#include <cstdio>

namespace af::gen {

namespace {

constexpr int kAnimFrameRate = 24;

// A path a decl may name: relative, inside the mod folder, and free of what a quoted decl string
// cannot hold (docs/formats.md §1.1: the loader refuses `..` and absolute paths).
void checkDeclPath(const std::string& path, const char* what) {
    const std::filesystem::path p(path);
    bool bad = path.empty() || p.is_absolute() || path.front() == '/' || path.front() == '\\' ||
               path.find(':') != std::string::npos || path.find('"') != std::string::npos;
    for (const auto& part : p) bad = bad || part == "..";
    for (char c : path) bad = bad || static_cast<unsigned char>(c) < 0x20;
    if (bad)
        throw OutputError(std::string("the ") + what + " path '" + path +
                          "' must be relative to the mod folder, without '..' or quotes (docs/formats.md §1.1)");
}

std::string fixed(Real value, int decimals = 2) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, static_cast<double>(value));
    return buffer;
}

}  // namespace

OutputFiles outputFiles(const std::string& name, const OutputRequest& request) {
    OutputFiles files{"af/" + name + ".af", "def/" + name + ".def", {}};
    if (request.animPath.empty()) files.anim = "models/" + name + "/af_pose.md5anim";
    return files;
}

Md5Anim bindPoseAnim(const Md5Mesh& mesh) {
    const Skeleton pose = skeletonFromMd5Mesh(mesh);
    std::vector<Md5JointPose> frame;
    Md5Bounds bounds{{1e30, 1e30, 1e30}, {-1e30, -1e30, -1e30}};
    for (std::size_t j = 0; j < pose.size(); ++j) {
        const JointTransform local = pose.local(j);
        frame.push_back({{local.position.x(), local.position.y(), local.position.z()}, md5FromRotation(local.rotation)});
        for (int k = 0; k < 3; ++k) {
            bounds.min[static_cast<std::size_t>(k)] = std::min(bounds.min[static_cast<std::size_t>(k)], pose.joints[j].position[k]);
            bounds.max[static_cast<std::size_t>(k)] = std::max(bounds.max[static_cast<std::size_t>(k)], pose.joints[j].position[k]);
        }
    }
    return makeMd5Anim(pose.names, pose.parents, {frame}, {bounds}, kAnimFrameRate, "af-gen: the bind pose");
}

std::string defText(const std::string& name, const std::string& meshPath, const std::string& animPath) {
    return "// " + name + ".def: written by af-gen from " + meshPath + " (docs/af-gen.md).\n\n" +
           "model " + name + " {\n\tmesh\t\t\t\"" + meshPath + "\"\n\tanim af_pose\t\"" + animPath + "\"\n}\n\n" +
           "entityDef " + name + " {\n\t\"spawnclass\"\t\t\t\"idAFEntity_Generic\"\n\t\"model\"\t\t\t\t\t\"" + name +
           "\"\n\t\"articulatedFigure\"\t\t\"" + name + "\"\n\t\"nodrop\"\t\t\t\t\"0\"\n}\n";
}

OutputFiles writeGenerated(const Generated& generated, const Md5Mesh& mesh, const OutputRequest& request) {
    const std::string& name = generated.decl.name;
    checkDeclPath(request.meshPath, "mesh");
    if (!request.animPath.empty()) checkDeclPath(request.animPath, "anim");
    const OutputFiles files = outputFiles(name, request);
    const std::string animPath = files.anim.empty() ? request.animPath : files.anim;

    std::vector<std::pair<std::string, std::string>> contents;  // relative path, text
    contents.emplace_back(files.af, writeAFFile(AFFile{files.af, {generated.decl}}));
    contents.emplace_back(files.def, defText(name, request.meshPath, animPath));
    if (!files.anim.empty()) contents.emplace_back(files.anim, writeMd5Anim(bindPoseAnim(mesh)));
    if (!request.overwrite)
        for (const auto& [path, text] : contents)
            if (std::filesystem::exists(request.outDir / path))
                throw OutputError((request.outDir / path).string() + " exists; --force replaces it");
    for (const auto& [path, text] : contents) {
        const std::filesystem::path target = request.outDir / path;
        std::error_code error;
        std::filesystem::create_directories(target.parent_path(), error);
        if (error) throw OutputError("cannot make the folder " + target.parent_path().string() + ": " + error.message());
        if (const WriteResult written = writeFileAtomically(target, text); !written.ok())
            throw OutputError(written.error);
    }
    return files;
}

std::string reportText(const Generated& g, const Skeleton& afPose) {
    std::string text = "figure " + g.decl.name + ": " + std::to_string(g.bodies.size()) + " bodies, " +
                       std::to_string(g.decl.constraints.size()) + " constraints, " +
                       std::to_string(afPose.size()) + " joints, total mass " + fixed(g.totalMass, 1) + "\n";
    for (std::size_t b = 0; b < g.bodies.size(); ++b) {
        const GenBody& body = g.bodies[b];
        const Vec3 size = body.shape.upper - body.shape.lower;
        text += "  " + body.name + ": " + toString(body.shape.type) + " " + fixed(size.x(), 1) + " x " +
                fixed(size.y(), 1) + " x " + fixed(size.z(), 1) + ", mass " + fixed(body.mass) + ", " +
                (body.shape.meshVertices > 0 ? std::to_string(body.shape.meshVertices) + " vertices"
                                             : std::string("sized from its bone")) +
                ", " + std::to_string(body.joints.size()) + " joints";
        if (b > 0)
            text += ", " + std::string(toString(g.decl.constraints[b - 1].type)) + " (" + toString(g.kinds[b]) +
                    ") to " + g.bodies[static_cast<std::size_t>(body.parent)].name;
        text += "\n";
    }
    return text;
}

}  // namespace af::gen
