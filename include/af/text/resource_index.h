#pragma once
// Finding a figure's files in mod folders, by name, as Doom 3 does (docs/formats.md §1.1,
// §2.3-§2.5; docs/figures.md §3.1).
//
// A root is a folder laid out like Doom's `base/`: `af/` holds `.af` files, `def/` holds `.def`
// files, and paths such as `models/humanoid/humanoid.md5mesh` are relative to it. Our repository
// root is such a folder.
//
// Search order. Roots are given lowest priority first, like Doom's base folder followed by a
// mod's `fs_game` folder: {base, mod}. Doom's search path works on FILES, and so does this index:
//  * A file path is looked up in the last root first, then in the earlier ones. In each root the
//    exact spelling is tried first, then a match ignoring case (mods made on Windows spell
//    `Models/Humanoid.MD5mesh` for `models/humanoid.md5mesh`; Linux file systems would miss it).
//  * Decl files: every `.af` under each root's `af/` and every `.def` under `def/` (recursively)
//    is listed. A relative path present in several roots (compared ignoring case) is read from
//    the last root only, so a mod replaces `def/humanoid.def` by shipping its own. The files are
//    then read in sorted order of their relative paths (ignoring case), whatever root they come
//    from, and a decl name that was already defined keeps its first definition with a warning,
//    as Doom's decl manager does. To override a decl, override the file that defines it.
//
// Names are canonicalised as Doom does (canonicalDeclName: case-insensitive, extension removed,
// `\` becomes `/`). A `.af` file with any error contributes no figure (as af-check treats it);
// a `.def` file with errors still contributes the decls that parsed, since its parser drops only
// the broken ones. Either way one broken file never stops the others from loading, and every
// diagnostic is kept in diagnostics().
//
// The index is built once and is immutable afterwards, except for the cache of md5 files, which
// loadMesh/loadAnim fill on first use; that cache is guarded by a mutex, so a const index may be
// shared between threads. Everything handed out stays valid while the index lives, and the
// shared pointers (figures, md5 files) outlive it.

#include "af/text/decl_af.h"
#include "af/text/decl_def.h"
#include "af/text/diagnostics.h"
#include "af/text/md5.h"

#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace af {

// One articulated figure and the file it was read from.
struct FigureEntry {
    DeclAF decl;
    std::string file;
};

// A place in a file where something is named (a `"model"` key, a `mesh` line), so that an error
// about the thing it names can point at it. An empty file means "named by the caller".
struct NamedAt {
    std::string file;
    SourceLocation where;
};

// A loaded md5 file. `mesh`/`anim` is null when the file was not found or did not parse; the
// reasons are in `diagnostics` (with the md5 file's own name and positions for parse errors).
struct MeshLoad {
    std::string path;  // the file that was read; empty when not found
    std::shared_ptr<const Md5Mesh> mesh;
    std::vector<Diagnostic> diagnostics;

    bool ok() const;
};

struct AnimLoad {
    std::string path;
    std::shared_ptr<const Md5Anim> anim;
    std::vector<Diagnostic> diagnostics;

    bool ok() const;
};

// Everything needed to build a ragdoll: what resolveAFEntity / resolveFigure found. The lookups
// go on after a failure, so one call reports every missing piece. Only when ok() is every
// pointer set and the af_pose anim known to fit the mesh (checkMd5AnimMatchesMesh).
struct AFResources {
    std::optional<EntityDef> entity;            // inheritance resolved; absent for resolveFigure
    std::shared_ptr<const FigureEntry> figure;  // the AF decl and its file
    std::optional<ModelDecl> model;             // inheritance resolved, or implicit (below)
    // The entityDef names the md5mesh directly and has an `anim af_pose` key (the iddevnet
    // example, docs/formats.md §2.5); `model` is then made up from those two keys.
    bool implicitModel = false;
    MeshLoad mesh;       // the model's `mesh`
    AnimLoad afPose;     // the model's `anim af_pose`
    std::vector<Diagnostic> diagnostics;  // every problem, including those of mesh and afPose

    bool ok() const;
    std::string formatDiagnostics() const;
};

class ResourceIndex {
public:
    // Lists and parses the decl files of `roots` (lowest priority first; see the top of this
    // file). Never throws for bad content or missing folders: those are diagnostics.
    explicit ResourceIndex(std::vector<std::filesystem::path> roots);
    ~ResourceIndex();
    // Moving keeps every pointer handed out valid (the state lives on the heap); a moved-from
    // index may only be destroyed or assigned to.
    ResourceIndex(ResourceIndex&&) noexcept;
    ResourceIndex& operator=(ResourceIndex&&) noexcept;

    const std::vector<std::filesystem::path>& roots() const;

    // Every problem met while indexing, each with its own file: parse errors and warnings of the
    // decl files, names defined twice, inheritance errors, unreadable folders.
    const std::vector<Diagnostic>& diagnostics() const;
    bool hasErrors() const;
    std::string formatDiagnostics() const;

    // The decl files read, in reading order (one per relative path, from the root that wins).
    const std::vector<std::string>& afFiles() const;
    const std::vector<std::string>& defFiles() const;

    // Figures in reading order; entityDefs and model decls with inheritance resolved.
    const std::vector<std::shared_ptr<const FigureEntry>>& figures() const;
    const DefCollection& defs() const;

    // Lookups by decl name, ignoring case and extension; nullptr when missing.
    const FigureEntry* findFigure(std::string_view name) const;
    const EntityDef* findEntityDef(std::string_view name) const;
    const ModelDecl* findModel(std::string_view name) const;

    // A file path relative to the roots (`\` or `/` separators), by the search order above.
    // Nothing when no root has it, or the path is absolute or has a `..`: mod folders are
    // untrusted, and nothing outside the roots is ever opened.
    std::optional<std::filesystem::path> resolvePath(std::string_view path) const;

    // Loads an md5 file found by resolvePath, parsed once and cached by the file found. `namedAt`
    // is where the path was written, for the "not found" error.
    MeshLoad loadMesh(std::string_view path, const NamedAt& namedAt = {}) const;
    AnimLoad loadAnim(std::string_view path, const NamedAt& namedAt = {}) const;

    // An AF entity: its entityDef, the figure of its `articulatedFigure` key (or `ragdoll`, the
    // key of actors), the model decl of its `model` key with that model's mesh and `af_pose`
    // anim, checked against each other.
    AFResources resolveAFEntity(std::string_view entityDefName) const;
    // A figure on its own, as the AF editor spawns it: the model comes from its
    // `settings { model "..." }`.
    AFResources resolveFigure(std::string_view figureName) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace af
