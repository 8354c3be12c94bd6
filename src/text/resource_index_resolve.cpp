// ResourceIndex: loading md5 files (cached) and resolving an AF entity or a figure to everything
// a ragdoll needs (docs/formats.md §2.4, §2.5; docs/figures.md §3.1 steps 1-2). Each step goes on
// after a failure where it can, so one call names every missing piece.

#include "resource_index_impl.h"

#include "af/text/strings.h"

#include <algorithm>

namespace af {

namespace {

bool noErrors(const std::vector<Diagnostic>& diagnostics) {
    return std::none_of(diagnostics.begin(), diagnostics.end(),
                        [](const Diagnostic& d) { return d.severity == Severity::Error; });
}

void append(std::vector<Diagnostic>& to, const std::vector<Diagnostic>& from) {
    to.insert(to.end(), from.begin(), from.end());
}

std::string inQuotes(std::string_view s) { return "\"" + std::string(s) + "\""; }

std::string count(std::size_t n, std::string_view what) {
    return std::to_string(n) + " " + std::string(what) + (n == 1 ? "" : "s");
}

Diagnostic errorAt(const NamedAt& at, std::string fallbackFile, std::string message) {
    return {Severity::Error, at.file.empty() ? std::move(fallbackFile) : at.file, at.where, std::move(message)};
}

bool endsWithIgnoringCase(std::string_view s, std::string_view suffix) {
    return s.size() >= suffix.size() && equalsIgnoreCase(s.substr(s.size() - suffix.size()), suffix);
}

template <class ParseResult, class Load>
std::shared_ptr<const ParseResult> cachedParse(std::mutex& mutex,
                                               std::map<std::string, std::shared_ptr<const ParseResult>>& cache,
                                               const std::string& file, Load load) {
    // Parsing under the lock keeps one parse per file even when two threads ask at once.
    const std::lock_guard lock(mutex);
    auto it = cache.find(file);
    if (it == cache.end()) it = cache.emplace(file, std::make_shared<const ParseResult>(load(file))).first;
    return it->second;
}

}  // namespace

bool MeshLoad::ok() const { return mesh != nullptr && noErrors(diagnostics); }
bool AnimLoad::ok() const { return anim != nullptr && noErrors(diagnostics); }

bool AFResources::ok() const {
    return figure != nullptr && model.has_value() && mesh.ok() && afPose.ok() && noErrors(diagnostics);
}

std::string AFResources::formatDiagnostics() const {
    std::string out;
    for (const Diagnostic& d : diagnostics) out += d.format() + '\n';
    return out;
}

std::optional<std::string> ResourceIndex::Impl::locate(std::string_view kind, std::string_view path,
                                                       const NamedAt& namedAt,
                                                       std::vector<Diagnostic>& diagnostics) const {
    const FileSearch search = findFile(path);
    if (search.found) return search.found->string();
    std::string message = std::string(kind) + " " + inQuotes(path);
    if (!search.problem.empty()) {
        message += " cannot be searched: " + search.problem;
    } else {
        message += " not found; looked in ";
        for (std::size_t i = 0; i < search.tried.size(); ++i) message += (i ? ", " : "") + search.tried[i].string();
        if (search.tried.empty()) message += "(no root folders)";
        else message += " (each also ignoring case)";
    }
    diagnostics.push_back(errorAt(namedAt, std::string(path), std::move(message)));
    return std::nullopt;
}

MeshLoad ResourceIndex::Impl::loadMesh(std::string_view path, const NamedAt& namedAt) const {
    MeshLoad out;
    const std::optional<std::string> file = locate("mesh", path, namedAt, out.diagnostics);
    if (!file) return out;
    out.path = *file;
    const auto parsed = cachedParse(cacheMutex, meshCache, *file, loadMd5MeshFile);
    out.diagnostics = parsed->diagnostics.all();
    // The aliasing constructor keeps the whole cached parse result alive while the mesh is used.
    if (parsed->ok()) out.mesh = std::shared_ptr<const Md5Mesh>(parsed, &parsed->mesh);
    return out;
}

AnimLoad ResourceIndex::Impl::loadAnim(std::string_view path, const NamedAt& namedAt) const {
    AnimLoad out;
    const std::optional<std::string> file = locate("anim", path, namedAt, out.diagnostics);
    if (!file) return out;
    out.path = *file;
    const auto parsed = cachedParse(cacheMutex, animCache, *file, loadMd5AnimFile);
    out.diagnostics = parsed->diagnostics.all();
    if (parsed->ok()) out.anim = std::shared_ptr<const Md5Anim>(parsed, &parsed->anim);
    return out;
}

NamedAt ResourceIndex::Impl::keyPlace(const EntityDef& entity, const DefKeyValue& key) const {
    if (!key.inheritedFrom.empty())
        if (const EntityDef* writer = rawDefs.findEntityDef(key.inheritedFrom)) return {writer->file, key.where};
    return {entity.file, key.where};
}

std::string ResourceIndex::Impl::fileThatSets(const ModelDecl& model, bool mesh) const {
    const ModelDecl* decl = rawDefs.findModel(model.name);
    // The bound stops a walk round an inheritance cycle (already reported by the resolver).
    for (std::size_t steps = 0; decl && steps <= rawDefs.models().size(); ++steps) {
        if (mesh ? !decl->mesh.empty() : decl->findAnim("af_pose") != nullptr) return decl->file;
        if (decl->inherit.empty()) break;
        decl = rawDefs.findModel(decl->inherit);
    }
    return model.file;
}

void ResourceIndex::Impl::lookupFigure(AFResources& out, std::string_view name, const NamedAt& namedAt) const {
    const std::string canonical = canonicalDeclName(name);
    if (const auto it = figureIndex.find(canonical); it != figureIndex.end()) {
        out.figure = figures[it->second];
        return;
    }
    std::string message = "figure " + inQuotes(name) + " not found; looked in " + declFolders("af") + " (" +
                          count(afFiles.size(), "file") + ", " + count(figures.size(), "figure") + ")";
    if (const auto broken = brokenFigureFiles.find(canonical); broken != brokenFigureFiles.end())
        message += "; " + broken->second + " has errors and was not loaded";
    out.diagnostics.push_back(errorAt(namedAt, topDeclFolder("af"), std::move(message)));
}

void ResourceIndex::Impl::lookupModel(AFResources& out, std::string_view name, const NamedAt& namedAt) const {
    if (const ModelDecl* model = defs.findModel(name)) {
        out.model = *model;
        loadModelFiles(out, nullptr, nullptr);
        return;
    }
    out.diagnostics.push_back(errorAt(namedAt, topDeclFolder("def"),
                                      "model " + inQuotes(name) + " not found; looked in " + declFolders("def") + " (" +
                                          count(defFiles.size(), "file") + ", " +
                                          count(defs.models().size(), "model decl") + ")"));
}

void ResourceIndex::Impl::loadModelFiles(AFResources& out, const NamedAt* meshAt, const NamedAt* animAt) const {
    const ModelDecl& model = *out.model;
    const NamedAt modelAt{model.file, model.where};
    if (model.mesh.empty()) {
        out.diagnostics.push_back(errorAt(modelAt, model.file, "model " + inQuotes(model.name) + " has no mesh"));
    } else {
        out.mesh = loadMesh(model.mesh, meshAt ? *meshAt : NamedAt{fileThatSets(model, true), model.meshWhere});
        append(out.diagnostics, out.mesh.diagnostics);
    }

    const ModelAnim* pose = model.findAnim("af_pose");
    if (!pose || pose->files.empty()) {
        std::string message = "model " + inQuotes(model.name) + " has no anim \"af_pose\", the pose the figure is "
                                                              "defined in";
        if (!model.anims.empty()) {
            message += " (its anims:";
            for (const ModelAnim& anim : model.anims) message += " " + anim.alias;
            message += ")";
        }
        out.diagnostics.push_back(errorAt(modelAt, model.file, std::move(message)));
    } else {
        // Several files make an anim with random variants; the pose is the first one.
        out.afPose = loadAnim(pose->files.front(), animAt ? *animAt : NamedAt{fileThatSets(model, false), pose->where});
        append(out.diagnostics, out.afPose.diagnostics);
    }

    if (out.mesh.mesh && out.afPose.anim) {
        Diagnostics fit(out.afPose.path);
        checkMd5AnimMatchesMesh(*out.afPose.anim, *out.mesh.mesh, fit);
        // The check's messages say "as in the mesh"; name the mesh, since the two files are far apart.
        for (Diagnostic d : fit.all()) {
            d.message += " (mesh " + out.mesh.path + " of model " + inQuotes(model.name) + ")";
            out.afPose.diagnostics.push_back(d);
            out.diagnostics.push_back(std::move(d));
        }
    }
}

MeshLoad ResourceIndex::loadMesh(std::string_view path, const NamedAt& namedAt) const {
    return impl_->loadMesh(path, namedAt);
}

AnimLoad ResourceIndex::loadAnim(std::string_view path, const NamedAt& namedAt) const {
    return impl_->loadAnim(path, namedAt);
}

AFResources ResourceIndex::resolveAFEntity(std::string_view entityDefName) const {
    const Impl& index = *impl_;
    AFResources out;
    const EntityDef* entity = index.defs.findEntityDef(entityDefName);
    if (!entity) {
        std::string message = "entityDef " + inQuotes(entityDefName) + " not found; looked in " +
                              index.declFolders("def") + " (" + count(index.defFiles.size(), "file") + ", " +
                              count(index.defs.entityDefs().size(), "entityDef") + ")";
        if (findFigure(entityDefName)) message += "; a figure has that name (resolveFigure loads a figure alone)";
        out.diagnostics.push_back({Severity::Error, index.topDeclFolder("def"), {}, std::move(message)});
        return out;
    }
    out.entity = *entity;
    const NamedAt entityAt{entity->file, entity->where};

    // idAFEntity_* read `articulatedFigure`; actors and animated props read `ragdoll`
    // (docs/formats.md §2.5).
    const DefKeyValue* figureKey = entity->find("articulatedFigure");
    if (!figureKey || figureKey->value.empty()) figureKey = entity->find("ragdoll");
    if (!figureKey || figureKey->value.empty()) {
        out.diagnostics.push_back(errorAt(entityAt, entity->file,
                                          "entityDef " + inQuotes(entity->name) +
                                              " names no figure: it has no \"articulatedFigure\" key (AF entities) "
                                              "and no \"ragdoll\" key (actors)"));
    } else {
        index.lookupFigure(out, figureKey->value, index.keyPlace(*entity, *figureKey));
    }

    const DefKeyValue* modelKey = entity->find("model");
    if (!modelKey || modelKey->value.empty()) {
        out.diagnostics.push_back(errorAt(entityAt, entity->file,
                                          "entityDef " + inQuotes(entity->name) +
                                              " has no \"model\" key, so the figure has no skeleton"));
        return out;
    }
    const NamedAt modelAt = index.keyPlace(*entity, *modelKey);
    if (index.defs.findModel(modelKey->value) || !endsWithIgnoringCase(modelKey->value, ".md5mesh")) {
        index.lookupModel(out, modelKey->value, modelAt);
        return out;
    }

    // The iddevnet form: "model" is the md5mesh itself and "anim af_pose" the pose. The GPL code
    // cannot load it; we make up the model decl they imply (docs/formats.md §2.5).
    const DefKeyValue* animKey = entity->find("anim af_pose");
    if (!animKey || animKey->value.empty()) {
        out.diagnostics.push_back(errorAt(modelAt, entity->file,
                                          "\"model\" names the mesh " + inQuotes(modelKey->value) +
                                              " directly; that needs an \"anim af_pose\" key next to it (the "
                                              "iddevnet form), or else a model decl with a mesh and an af_pose anim"));
        return out;
    }
    const NamedAt animAt = index.keyPlace(*entity, *animKey);
    ModelDecl implicit;
    implicit.name = canonicalDeclName(modelKey->value);
    implicit.writtenName = modelKey->value;
    implicit.file = modelAt.file;
    implicit.where = modelAt.where;
    implicit.mesh = modelKey->value;
    implicit.meshWhere = modelAt.where;
    implicit.anims.push_back({"af_pose", {animKey->value}, false, animAt.where});
    out.model = std::move(implicit);
    out.implicitModel = true;
    index.loadModelFiles(out, &modelAt, &animAt);
    return out;
}

AFResources ResourceIndex::resolveFigure(std::string_view figureName) const {
    const Impl& index = *impl_;
    AFResources out;
    index.lookupFigure(out, figureName, {});
    if (!out.figure) return out;
    const FigureEntry& figure = *out.figure;
    // The settings keep no position of their own; the decl's name is the nearest place to point at.
    const NamedAt figureAt{figure.file, figure.decl.where};
    if (figure.decl.settings.model.empty()) {
        out.diagnostics.push_back(errorAt(figureAt, figure.file,
                                          "figure " + inQuotes(figure.decl.name) +
                                              " names no model in its settings, so its skeleton is unknown"));
        return out;
    }
    index.lookupModel(out, figure.decl.settings.model, figureAt);
    return out;
}

}  // namespace af
