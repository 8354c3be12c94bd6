// ResourceIndex: listing and parsing the decl files of the roots, and the lookups by name
// (the search order is explained in af/text/resource_index.h).

#include "resource_index_impl.h"

#include "af/text/af_parser.h"
#include "af/text/strings.h"

#include <algorithm>

namespace af {

namespace {

// One decl file chosen for reading: the relative path as the winning root spells it.
struct DeclFileChoice {
    std::size_t root = 0;
    std::string relative;  // below the root's decl folder, `/` separators
    fs::path path;
};

// The files of one decl folder over all roots, keyed by their relative path ignoring case; a
// later root replaces an earlier one's file, as Doom's search path does. std::map keeps the keys
// sorted, which is the reading order.
std::map<std::string, DeclFileChoice> chooseDeclFiles(const std::vector<fs::path>& roots, std::string_view folder,
                                                      std::string_view extension,
                                                      std::vector<Diagnostic>& diagnostics) {
    std::map<std::string, DeclFileChoice> chosen;
    for (std::size_t r = 0; r < roots.size(); ++r) {
        // `AF/` or `Def/` in a mod made on Windows is still the decl folder.
        const std::optional<fs::path> dir = findIgnoringCase(roots[r], {std::string(folder)}, true);
        if (!dir) continue;
        std::map<std::string, std::string> seenInRoot;  // lower-case key -> spelling kept
        for (std::string& relative : listFilesRecursively(*dir, extension, diagnostics)) {
            const std::string key = toLower(relative);
            if (const auto seen = seenInRoot.find(key); seen != seenInRoot.end()) {
                diagnostics.push_back({Severity::Warning, (*dir / relative).string(), {},
                                       "this file and " + seen->second +
                                           " differ only in case; Doom cannot tell them apart, so this one is "
                                           "ignored"});
                continue;
            }
            seenInRoot.emplace(key, relative);
            fs::path path = *dir / relative;
            chosen[key] = DeclFileChoice{r, std::move(relative), std::move(path)};
        }
    }
    return chosen;
}

std::string where(const std::string& file, SourceLocation at) {
    std::string out = file;
    if (at.line > 0) out += ':' + std::to_string(at.line) + ':' + std::to_string(at.column);
    return out;
}

}  // namespace

void ResourceIndex::Impl::build() {
    std::error_code ec;
    for (const fs::path& root : roots)
        if (!fs::is_directory(root, ec))
            diagnostics.push_back({Severity::Error, root.string(), {}, "root folder does not exist or is not a folder"});

    for (auto& [key, choice] : chooseDeclFiles(roots, "af", ".af", diagnostics)) {
        AFParseResult parsed = loadAFFile(choice.path.string());
        afFiles.push_back(choice.path.string());
        const std::vector<Diagnostic>& found = parsed.diagnostics.all();
        diagnostics.insert(diagnostics.end(), found.begin(), found.end());
        if (!parsed.ok()) {
            // Nothing of a broken .af is used, but a later "not found" can say why.
            const std::string stem = canonicalDeclName(fs::path(choice.relative).filename().string());
            brokenFigureFiles.emplace(stem, choice.path.string());
            for (const DeclAF& decl : parsed.file.decls) brokenFigureFiles.emplace(decl.name, choice.path.string());
            continue;
        }
        for (DeclAF& decl : parsed.file.decls) {
            if (const auto earlier = figureIndex.find(decl.name); earlier != figureIndex.end()) {
                const FigureEntry& first = *figures[earlier->second];
                diagnostics.push_back({Severity::Warning, choice.path.string(), decl.where,
                                       "figure '" + decl.name + "' is already defined at " +
                                           where(first.file, first.decl.where) +
                                           "; this definition is ignored (the first one read wins, as in Doom)"});
                continue;
            }
            figureIndex.emplace(decl.name, figures.size());
            figures.push_back(std::make_shared<const FigureEntry>(FigureEntry{std::move(decl), choice.path.string()}));
        }
    }

    for (auto& [key, choice] : chooseDeclFiles(roots, "def", ".def", diagnostics)) {
        const DefParseResult parsed = loadDefFile(choice.path.string());
        defFiles.push_back(choice.path.string());
        const std::vector<Diagnostic>& found = parsed.diagnostics.all();
        diagnostics.insert(diagnostics.end(), found.begin(), found.end());
        // The def parser drops only the decls it could not read, so the rest of a big mod .def
        // file stays usable.
        rawDefs.add(parsed.file, diagnostics);
    }
    ResolvedDefs resolved = resolveDefInheritance(rawDefs);
    diagnostics.insert(diagnostics.end(), resolved.diagnostics.begin(), resolved.diagnostics.end());
    defs = std::move(resolved.decls);
}

ResourceIndex::ResourceIndex(std::vector<std::filesystem::path> roots) : impl_(std::make_unique<Impl>()) {
    impl_->roots = std::move(roots);
    impl_->build();
}

ResourceIndex::~ResourceIndex() = default;
ResourceIndex::ResourceIndex(ResourceIndex&&) noexcept = default;
ResourceIndex& ResourceIndex::operator=(ResourceIndex&&) noexcept = default;

const std::vector<std::filesystem::path>& ResourceIndex::roots() const { return impl_->roots; }
const std::vector<Diagnostic>& ResourceIndex::diagnostics() const { return impl_->diagnostics; }

bool ResourceIndex::hasErrors() const {
    return std::any_of(impl_->diagnostics.begin(), impl_->diagnostics.end(),
                       [](const Diagnostic& d) { return d.severity == Severity::Error; });
}

std::string ResourceIndex::formatDiagnostics() const {
    std::string out;
    for (const Diagnostic& d : impl_->diagnostics) out += d.format() + '\n';
    return out;
}

const std::vector<std::string>& ResourceIndex::afFiles() const { return impl_->afFiles; }
const std::vector<std::string>& ResourceIndex::defFiles() const { return impl_->defFiles; }
const std::vector<std::shared_ptr<const FigureEntry>>& ResourceIndex::figures() const { return impl_->figures; }
const DefCollection& ResourceIndex::defs() const { return impl_->defs; }

const FigureEntry* ResourceIndex::findFigure(std::string_view name) const {
    const auto it = impl_->figureIndex.find(canonicalDeclName(name));
    return it == impl_->figureIndex.end() ? nullptr : impl_->figures[it->second].get();
}

const EntityDef* ResourceIndex::findEntityDef(std::string_view name) const { return impl_->defs.findEntityDef(name); }
const ModelDecl* ResourceIndex::findModel(std::string_view name) const { return impl_->defs.findModel(name); }

std::optional<std::filesystem::path> ResourceIndex::resolvePath(std::string_view path) const {
    return impl_->findFile(path).found;
}

}  // namespace af
