#pragma once
// af-gen's files: the figure through the canonical .af writer, a .def with its model decl and AF
// entityDef, and, when no af_pose anim is given, one of the mesh's bind pose; and the report.

#include "gen_figure.h"

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace af::gen {

// A file that cannot be written, or a path a decl cannot name: the message says which and why.
struct OutputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct OutputRequest {
    std::string meshPath;  // relative to the mod folder, as the model decl names it
    std::string animPath;  // the same for the af_pose anim; empty: write the bind pose's
    std::filesystem::path outDir;
    bool overwrite = false;  // replace files that exist
};

// The relative paths (under outDir) of what writeGenerated writes.
struct OutputFiles {
    std::string af, def, anim;  // anim empty when the request gives one
};
OutputFiles outputFiles(const std::string& name, const OutputRequest& request);

// A one-frame anim of the mesh's bind pose: the af_pose when none is given (docs/formats.md §2.3).
Md5Anim bindPoseAnim(const Md5Mesh& mesh);

// The .def text: `model NAME` naming the mesh and the af_pose anim, `entityDef NAME` an
// idAFEntity_Generic of that model and figure.
std::string defText(const std::string& name, const std::string& meshPath, const std::string& animPath);

// Writes every file, each through a temporary file and a rename (af/text/atomic_write.h). Throws
// OutputError, having written nothing, for a path a decl cannot name (absolute, with `..`, with a
// quote) or a file that exists without `overwrite`; after a failed write, the files before it stay.
OutputFiles writeGenerated(const Generated& generated, const Md5Mesh& mesh, const OutputRequest& request);

// What was made, for the terminal: each body with its joints, shape, mass and what sized it;
// each constraint with its kind.
std::string reportText(const Generated& generated, const Skeleton& afPose);

}  // namespace af::gen
