// af-gen: writes a working ragdoll for an md5mesh skeleton (docs/af-gen.md): the .af figure, a
// .def with its model decl and AF entityDef, and, without --anim, an af_pose anim of the bind pose.
// Run from the mod folder, so that the paths given are the ones the model decl names.
//
// Exit status: 0 when the files are written (the figure's warnings, if any, are printed), 2 for
// bad usage or input (an unreadable mesh or anim, an anim of another skeleton, a skeleton that
// makes no figure, a file that exists or cannot be written); then nothing is written, but for the
// files before one whose write failed.

#include "command_line_usage.h"
#include "gen_output.h"

#include "af/figure/figure.h"
#include "af/text/af_parser.h"
#include "af/text/af_writer.h"
#include "af/text/strings.h"

#include <CLI/CLI.hpp>

#include <iostream>

namespace {

struct Options {
    std::string mesh;
    std::string anim;
    std::string name;
    std::string out = ".";
    bool force = false;
    af::gen::GenOptions gen;
};

struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// A decl name: a bare word that every decl file reads the same way.
std::string declName(const Options& o) {
    const std::string name = af::toLower(o.name.empty() ? std::filesystem::path(o.mesh).stem().string() : o.name);
    bool good = !name.empty();
    for (char c : name) good = good && (std::isalnum(static_cast<unsigned char>(c)) || c == '_');
    if (!good) throw InputError("the name '" + name + "' must be letters, digits and '_' (give one with --name)");
    return name;
}

// A path as the decl will name it: '/' separators, no leading "./".
std::string declPath(std::string path) {
    for (char& c : path)
        if (c == '\\') c = '/';
    while (path.starts_with("./")) path.erase(0, 2);
    return path;
}

int generate(Options& o) {
    using namespace af;
    o.gen.name = declName(o);
    const std::string meshPath = declPath(o.mesh);
    const Md5MeshWithSkin loaded = loadMd5MeshWithSkin(meshPath);
    const Md5MeshParseResult& mesh = loaded.parsed;
    if (!mesh.ok()) throw InputError(mesh.diagnostics.formatAll());
    Skeleton afPose = skeletonFromMd5Mesh(mesh.mesh);
    if (!o.anim.empty()) {
        Md5AnimParseResult anim = loadMd5AnimFile(declPath(o.anim));
        if (anim.ok()) checkMd5AnimMatchesMesh(anim.anim, mesh.mesh, anim.diagnostics);
        if (!anim.ok()) throw InputError(anim.diagnostics.formatAll());
        afPose = skeletonFromMd5Anim(anim.anim, 0);
    }

    gen::Generated generated;
    try {
        generated = gen::generateFigure(loaded.skin, afPose, o.gen);
    } catch (const std::invalid_argument& e) {
        throw InputError(meshPath + ": " + e.what());
    }
    const gen::OutputRequest request{meshPath, o.anim.empty() ? std::string() : declPath(o.anim), o.out, o.force};
    const gen::OutputFiles files = gen::outputFiles(o.gen.name, request);

    // The figure as a user will load it, before anything is written: the text the writer makes,
    // parsed and built on the af_pose. One that does not build is a skeleton we cannot make a
    // figure of; its warnings, if any, are printed.
    const AFParseResult parsed = parseAF(writeDecl(generated.decl), files.af);
    if (!parsed.ok()) throw InputError("cannot make a figure of this skeleton:\n" + parsed.diagnostics.formatAll());
    const FigureResult built = buildFigure(parsed.file.decls.front(), afPose, files.af);
    if (!built.ok()) throw InputError("cannot make a figure of this skeleton:\n" + built.formatDiagnostics());
    std::cerr << built.formatDiagnostics();

    gen::writeGenerated(generated, mesh.mesh, request);
    std::cout << gen::reportText(generated, afPose);
    for (const std::string& f : {files.af, files.def, files.anim})
        if (!f.empty()) std::cout << "wrote " << (std::filesystem::path(o.out) / f).string() << '\n';
    std::cout << "try: af-sim --root . --root " << o.out << " --entity " << o.gen.name << '\n';
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app{"Writes a ragdoll (.af, .def) for an md5mesh skeleton. Run it from the mod folder."};
    app.add_option("mesh", o.mesh, ".md5mesh, relative to the mod folder")->required();
    app.add_option("--anim", o.anim, "the af_pose .md5anim (default: the mesh's bind pose, written under OUT/models/)");
    app.add_option("--name", o.name, "decl, model and entityDef name (default: the mesh's file name)");
    app.add_option("--out", o.out, "folder the af/, def/ and models/ files go into")->capture_default_str();
    app.add_option("--keep", o.gen.keep, "joints that get a body of their own (repeat, or comma-separated)")->delimiter(',');
    app.add_option("--merge", o.gen.merge, "joints their parent's body contains (repeat, or comma-separated)")->delimiter(',');
    app.add_option("--total-mass", o.gen.totalMass, "the figure's mass (default: from its size, as our humanoid's)")
        ->check(CLI::PositiveNumber);
    app.add_flag("--force", o.force, "replace files that exist");
    if (const auto exitStatus = af::tools::parseCommandLine(app, argc, argv, "af-gen")) return *exitStatus;
    try {
        return generate(o);
    } catch (const std::exception& e) {
        // Diagnostics end in a newline of their own.
        std::string message = e.what();
        while (!message.empty() && message.back() == '\n') message.pop_back();
        std::cerr << "af-gen: " << message << '\n';
        return 2;
    }
}
