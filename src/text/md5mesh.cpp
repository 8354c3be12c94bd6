// `.md5mesh` files (docs/formats.md §2.1): the bind-pose skeleton is kept; the mesh blocks are
// read to prove the file well-formed, and their vertices and weights kept only when asked for
// (md5_skin.h).

#include "af/text/md5.h"
#include "af/text/md5_skin.h"
#include "af/text/strings.h"
#include "md5_common.h"

#include <algorithm>

namespace af {

using namespace md5detail;

namespace {

std::string ordinalOf(int i, int count, std::string_view countName) {
    return std::to_string(i + 1) + " of " + std::to_string(count) + " (" + std::string(countName) + ")";
}

class Md5MeshParser {
public:
    // `skin`, when given, receives every block's vertices and weights.
    Md5MeshParser(std::string_view text, Diagnostics& diagnostics, std::vector<Md5SkinSection>* skin)
        : in_(text, diagnostics), skin_(skin) {}

    void parse(Md5Mesh& mesh) {
        mesh.commandLine = readHeader(in_);
        const int jointCount = readCount(in_, "numJoints", 1);
        const int meshCount = readCount(in_, "numMeshes", 0);

        expectKeyword(in_, "joints");
        in_.expectPunctuation("{", "after joints");
        for (int i = 0; i < jointCount; ++i) mesh.joints.push_back(parseJoint(mesh, i, jointCount));
        in_.expectPunctuation("}", "after the " + std::to_string(jointCount) + " joints (numJoints)");

        for (int i = 0; i < meshCount; ++i) {
            expectKeyword(in_, "mesh", ordinalOf(i, meshCount, "numMeshes"));
            mesh.meshes.push_back(parseMeshBlock(jointCount));
        }
        expectEnd(in_, "the " + std::to_string(meshCount) + " meshes (numMeshes)");
    }

private:
    Md5Joint parseJoint(const Md5Mesh& mesh, int index, int jointCount) {
        Md5Joint joint;
        const Token name = readWord(in_, "the name of joint " + ordinalOf(index, jointCount, "numJoints"));
        joint.name = name.text;
        joint.where = name.where;
        // Joint names are matched ignoring case everywhere in the AF code, so two joints that
        // differ only in case could not be told apart.
        for (const Md5Joint& other : mesh.joints) {
            if (equalsIgnoreCase(other.name, joint.name)) {
                failAt(in_, name.where, "expected a unique joint name, found " + describe(name) + " (joint " +
                                            std::to_string(&other - mesh.joints.data()) + " at line " +
                                            std::to_string(other.where.line) + " has the same name, ignoring case)");
            }
        }

        SourceLocation where;
        joint.parent = in_.readInt("the parent index", &where);
        if (index == 0 && joint.parent != -1)
            failAt(in_, where, "expected parent -1 for the first joint (the root), found '" +
                                   std::to_string(joint.parent) + "'");
        if (index > 0 && (joint.parent < 0 || joint.parent >= index))
            failAt(in_, where, "expected a parent index from 0 to " + std::to_string(index - 1) +
                                   " (a parent comes before its children), found '" +
                                   std::to_string(joint.parent) + "'");

        joint.position = readTuple3(in_, "the joint position");
        joint.orientation = readQuat(in_, "the joint orientation");
        return joint;
    }

    Md5MeshSection parseMeshBlock(int jointCount) {
        Md5MeshSection section;
        Md5SkinSection* skin = skin_ ? &skin_->emplace_back() : nullptr;
        in_.expectPunctuation("{", "after mesh");
        if (in_.peek().type == TokenType::Name && in_.peek().text == "name") {
            in_.next();
            section.name = readWord(in_, "a mesh name").text;
        }
        expectKeyword(in_, "shader");
        section.shader = readWord(in_, "a shader name").text;

        section.vertexCount = readCount(in_, "numverts", 0);
        int weightsNeeded = 0;
        for (int i = 0; i < section.vertexCount; ++i) {
            expectKeyword(in_, "vert", ordinalOf(i, section.vertexCount, "numverts"));
            in_.readInt("the vertex index");
            Real st[2];
            readTuple(in_, st, 2, "the texture coordinates");
            SourceLocation where;
            const int first = in_.readInt("the first weight", &where);
            if (first < 0)
                failAt(in_, where, "expected a first weight of 0 or more, found '" + std::to_string(first) + "'");
            const int count = in_.readInt("the weight count", &where);
            if (count <= 0)
                failAt(in_, where, "expected a weight count greater than 0, found '" + std::to_string(count) + "'");
            weightsNeeded = std::max(weightsNeeded, first + count);
            if (skin) skin->vertices.push_back({first, count});
        }

        section.triangleCount = readCount(in_, "numtris", 0);
        for (int i = 0; i < section.triangleCount; ++i) {
            expectKeyword(in_, "tri", ordinalOf(i, section.triangleCount, "numtris"));
            in_.readInt("the triangle index");
            for (int k = 0; k < 3; ++k) {
                SourceLocation where;
                const int v = in_.readInt("a triangle vertex", &where);
                if (v < 0 || v >= section.vertexCount)
                    failAt(in_, where, "expected a vertex index from 0 to " + std::to_string(section.vertexCount - 1) +
                                           ", found '" + std::to_string(v) + "'");
            }
        }

        expectKeyword(in_, "numweights");
        SourceLocation countWhere;
        section.weightCount = in_.readInt("numweights", &countWhere);
        // Doom only warns here, then reads weights past the end of its array.
        if (section.weightCount < weightsNeeded)
            failAt(in_, countWhere, "expected numweights of at least " + std::to_string(weightsNeeded) +
                                        " (the vertices use that many), found '" +
                                        std::to_string(section.weightCount) + "'");
        for (int i = 0; i < section.weightCount; ++i) {
            expectKeyword(in_, "weight", ordinalOf(i, section.weightCount, "numweights"));
            in_.readInt("the weight index");
            SourceLocation where;
            const int joint = in_.readInt("the weight's joint", &where);
            if (joint < 0 || joint >= jointCount)
                failAt(in_, where, "expected a joint index from 0 to " + std::to_string(jointCount - 1) + ", found '" +
                                       std::to_string(joint) + "'");
            const Real bias = in_.readFloat("the weight bias");
            const Real3 position = readTuple3(in_, "the weight position");
            if (skin) skin->weights.push_back({joint, bias, position});
        }
        in_.expectPunctuation("}", "after the " + std::to_string(section.weightCount) + " weights (numweights)");
        return section;
    }

    TokenReader in_;
    std::vector<Md5SkinSection>* skin_;
};

}  // namespace

int Md5Mesh::findJoint(std::string_view name) const {
    for (std::size_t i = 0; i < joints.size(); ++i)
        if (equalsIgnoreCase(joints[i].name, name)) return static_cast<int>(i);
    return -1;
}

Md5MeshParseResult parseMd5Mesh(std::string_view text, std::string fileName) {
    Md5MeshParseResult result{{}, Diagnostics(std::move(fileName))};
    Md5MeshParser parser(text, result.diagnostics, nullptr);
    try {
        parser.parse(result.mesh);
    } catch (const ParseAbort&) {
    }
    return result;
}

Md5MeshWithSkin parseMd5MeshWithSkin(std::string_view text, std::string fileName) {
    Md5MeshWithSkin result{{{}, Diagnostics(std::move(fileName))}, {}};
    Md5MeshParser parser(text, result.parsed.diagnostics, &result.skin);
    try {
        parser.parse(result.parsed.mesh);
    } catch (const ParseAbort&) {
    }
    return result;
}

Md5MeshParseResult loadMd5MeshFile(const std::string& path) {
    if (std::optional<std::string> text = readWholeFile(path)) return parseMd5Mesh(*text, path);
    Md5MeshParseResult result{{}, Diagnostics(path)};
    result.diagnostics.error({}, "cannot open the file for reading");
    return result;
}

Md5MeshWithSkin loadMd5MeshWithSkin(const std::string& path) {
    if (std::optional<std::string> text = readWholeFile(path)) return parseMd5MeshWithSkin(*text, path);
    return {loadMd5MeshFile(path), {}};
}

}  // namespace af
