#pragma once
// The inside of ResourceIndex, shared by its three source files: indexing and lookups
// (resource_index.cpp), file search (resource_index_paths.cpp), md5 loading and the AF
// resolution (resource_index_resolve.cpp).

#include "af/text/resource_index.h"

#include <map>
#include <mutex>

namespace af {

namespace fs = std::filesystem;

// The result of a file search, with what was tried, for "not found" messages.
struct FileSearch {
    std::optional<fs::path> found;
    std::vector<fs::path> tried;  // in search order, highest priority first
    std::string problem;          // set when the path cannot be searched at all (absolute, a `..`)
};

// A path as components: `\` and `/` both separate, empty and `.` components are dropped.
// Nothing for a path with a `..`, which would leave the root.
std::optional<std::vector<std::string>> splitGamePath(std::string_view path);

// A path that names a place outside any root: it starts with `/` or `\` or a drive letter.
bool isAbsoluteGamePath(std::string_view path);

// Finds `components` below `base`: at each level the exact name first, then names that match
// ignoring case, in sorted order, backtracking when a branch does not lead to the wanted kind of
// entry (a regular file, or a folder when `wantFolder`).
std::optional<fs::path> findIgnoringCase(const fs::path& base, const std::vector<std::string>& components,
                                         bool wantFolder);

// Every regular file below `folder` whose extension is `extension` ignoring case, as paths
// relative to `folder` with `/` separators, sorted ignoring case (exact order breaks ties).
// Problems reading folders are warnings.
std::vector<std::string> listFilesRecursively(const fs::path& folder, std::string_view extension,
                                              std::vector<Diagnostic>& diagnostics);

struct ResourceIndex::Impl {
    std::vector<fs::path> roots;  // as given: lowest priority first
    std::vector<Diagnostic> diagnostics;
    std::vector<std::string> afFiles;
    std::vector<std::string> defFiles;

    std::vector<std::shared_ptr<const FigureEntry>> figures;
    std::map<std::string, std::size_t, std::less<>> figureIndex;
    // Decl names (and file stems) of .af files that had errors, to explain a missing figure.
    std::map<std::string, std::string, std::less<>> brokenFigureFiles;

    DefCollection rawDefs;  // as parsed, to tell which file an inherited mesh or anim came from
    DefCollection defs;     // inheritance resolved

    mutable std::mutex cacheMutex;
    mutable std::map<std::string, std::shared_ptr<const Md5MeshParseResult>> meshCache;
    mutable std::map<std::string, std::shared_ptr<const Md5AnimParseResult>> animCache;

    void build();  // lists and parses the decl files of `roots`

    FileSearch findFile(std::string_view path) const;
    // "/mod/def, /base/def": a decl folder of every root, highest priority first.
    std::string declFolders(std::string_view folder) const;
    // Where "not found" errors about a decl folder go when no key names the decl.
    std::string topDeclFolder(std::string_view folder) const;

    // resource_index_resolve.cpp
    MeshLoad loadMesh(std::string_view path, const NamedAt& namedAt) const;
    AnimLoad loadAnim(std::string_view path, const NamedAt& namedAt) const;
    // The file that was read for `path`, or nothing after adding a "not found" error.
    std::optional<std::string> locate(std::string_view kind, std::string_view path, const NamedAt& namedAt,
                                      std::vector<Diagnostic>& diagnostics) const;
    // Where an entityDef's key was written; an inherited key was written in its parent's file.
    NamedAt keyPlace(const EntityDef& entity, const DefKeyValue& key) const;
    // The file of the decl in `model`'s inheritance chain that wrote its mesh (or its af_pose anim).
    std::string fileThatSets(const ModelDecl& model, bool mesh) const;
    void lookupFigure(AFResources& out, std::string_view name, const NamedAt& namedAt) const;
    void lookupModel(AFResources& out, std::string_view name, const NamedAt& namedAt) const;
    // Loads out.model's mesh and af_pose anim; a null place means "where the model decl wrote it".
    void loadModelFiles(AFResources& out, const NamedAt* meshAt, const NamedAt* animAt) const;
};

}  // namespace af
