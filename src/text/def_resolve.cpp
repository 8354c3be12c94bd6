// The collection of .def decls and inheritance resolution (docs/formats.md §2.4, §2.5).

#include "af/text/decl_def.h"
#include "af/text/strings.h"

#include <algorithm>
#include <cctype>
#include <optional>

namespace af {

namespace {

Diagnostic diagnostic(Severity severity, const std::string& file, SourceLocation where, std::string message) {
    return {severity, file, where, std::move(message)};
}

// Doom's idAnim::Name(): the alias without its variant number ("walk2" is a "walk").
std::string_view withoutVariant(std::string_view alias) {
    std::size_t end = alias.size();
    while (end > 1 && std::isdigit(static_cast<unsigned char>(alias[end - 1]))) --end;
    return alias.substr(0, end);
}

enum class Visit { Pending, Active, Done };

// Walks the inheritance graph depth first so that each parent is resolved before its children
// copy from it; a parent met while still Active closes a cycle.
template <class Decl>
class Resolver {
public:
    Resolver(const std::vector<Decl>& decls, std::vector<Diagnostic>& diagnostics)
        : out_(decls), state_(decls.size(), Visit::Pending), diagnostics_(diagnostics) {}

    std::vector<Decl>& decls() { return out_; }

    // Returns the index of the parent to inherit from once it is resolved, or nothing after
    // reporting why not.
    template <class Find>
    std::optional<std::size_t> enterParent(const Decl& child, std::string_view parentName, SourceLocation where,
                                           std::string_view kind, Find find, std::string_view otherKindNote) {
        const std::optional<std::size_t> parent = find(parentName);
        if (!parent) {
            diagnostics_.push_back(diagnostic(Severity::Error, child.file, where,
                                              std::string(kind) + " '" + child.name + "' inherits '" +
                                                  std::string(parentName) + "', which is not defined" +
                                                  std::string(otherKindNote)));
            return std::nullopt;
        }
        if (state_[*parent] == Visit::Active) {
            std::string chain;
            const auto from = std::find(stack_.begin(), stack_.end(), *parent);
            for (auto it = from; it != stack_.end(); ++it) chain += out_[*it].name + " -> ";
            chain += out_[*parent].name;
            diagnostics_.push_back(diagnostic(Severity::Error, child.file, where,
                                              std::string(kind) + " '" + child.name + "' inherits '" +
                                                  out_[*parent].name + "', which is an inheritance cycle (" + chain +
                                                  "); that inherit is ignored"));
            return std::nullopt;
        }
        return parent;
    }

    bool begin(std::size_t i) {
        if (state_[i] != Visit::Pending) return false;
        state_[i] = Visit::Active;
        stack_.push_back(i);
        return true;
    }

    void end(std::size_t i) {
        stack_.pop_back();
        state_[i] = Visit::Done;
    }

    std::vector<Diagnostic>& diagnostics() { return diagnostics_; }

private:
    std::vector<Decl> out_;
    std::vector<Visit> state_;
    std::vector<std::size_t> stack_;
    std::vector<Diagnostic>& diagnostics_;
};

void resolveEntity(Resolver<EntityDef>& r, const DefCollection& decls, std::size_t i) {
    if (!r.begin(i)) return;
    // The vector is never resized, so this reference survives the recursion below.
    EntityDef& def = r.decls()[i];

    // Doom sets classname after parsing, so it overrides a written one.
    auto classname = std::find_if(def.keyValues.begin(), def.keyValues.end(),
                                  [](const DefKeyValue& kv) { return equalsIgnoreCase(kv.key, "classname"); });
    if (classname != def.keyValues.end()) classname->value = def.name;
    else def.keyValues.push_back({"classname", def.name, def.where, {}});

    std::vector<DefKeyValue> inherits;
    std::erase_if(def.keyValues, [&](const DefKeyValue& kv) {
        const bool inherit = kv.key.size() >= 7 && equalsIgnoreCase(std::string_view(kv.key).substr(0, 7), "inherit");
        if (inherit) inherits.push_back(kv);
        return inherit;
    });

    auto find = [&](std::string_view name) -> std::optional<std::size_t> {
        if (const EntityDef* p = decls.findEntityDef(name))
            return static_cast<std::size_t>(p - decls.entityDefs().data());
        return std::nullopt;
    };
    for (const DefKeyValue& inherit : inherits) {
        const std::string note = decls.findModel(inherit.value) ? " (there is a model decl of that name)" : "";
        const std::optional<std::size_t> parent =
            r.enterParent(def, inherit.value, inherit.where, "entityDef", find, note);
        if (!parent) continue;
        resolveEntity(r, decls, *parent);
        const EntityDef& from = r.decls()[*parent];
        for (const DefKeyValue& kv : from.keyValues) {
            if (def.find(kv.key)) continue;
            DefKeyValue copy = kv;
            if (copy.inheritedFrom.empty()) copy.inheritedFrom = from.name;
            def.keyValues.push_back(std::move(copy));
        }
    }
    r.end(i);
}

void mergeModel(ModelDecl& child, const ModelDecl& parent, std::vector<Diagnostic>& diagnostics) {
    if (child.mesh.empty()) child.mesh = parent.mesh, child.meshWhere = parent.meshWhere;
    if (child.skin.empty()) child.skin = parent.skin;
    if (!child.offset) child.offset = parent.offset;

    std::vector<ModelChannel> channels = parent.channels;
    for (const ModelChannel& own : child.channels) {
        auto same = std::find_if(channels.begin(), channels.end(),
                                 [&](const ModelChannel& c) { return equalsIgnoreCase(c.name, own.name); });
        if (same != channels.end()) *same = own;
        else channels.push_back(own);
    }
    child.channels = std::move(channels);

    std::vector<ModelAnim> anims = parent.anims;
    for (const ModelRemove& remove : child.removes) {
        const std::size_t removed = std::erase_if(anims, [&](const ModelAnim& a) {
            return a.alias == remove.alias || withoutVariant(a.alias) == remove.alias;
        });
        if (removed == 0)
            diagnostics.push_back(diagnostic(Severity::Warning, child.file, remove.where,
                                             "remove '" + remove.alias + "' matches no anim inherited from '" +
                                                 parent.name + "' (Doom 3 rejects the model decl)"));
    }
    for (const ModelAnim& own : child.anims) {
        auto same = std::find_if(anims.begin(), anims.end(), [&](const ModelAnim& a) { return a.alias == own.alias; });
        if (same != anims.end()) *same = own;
        else anims.push_back(own);
    }
    child.anims = std::move(anims);
}

void resolveModel(Resolver<ModelDecl>& r, const DefCollection& decls, std::size_t i) {
    if (!r.begin(i)) return;
    const ModelDecl& written = r.decls()[i];
    std::optional<std::size_t> parent;
    if (!written.inherit.empty()) {
        auto find = [&](std::string_view name) -> std::optional<std::size_t> {
            if (const ModelDecl* p = decls.findModel(name)) return static_cast<std::size_t>(p - decls.models().data());
            return std::nullopt;
        };
        const std::string note =
            decls.findEntityDef(written.inherit) ? " as a model decl (there is an entityDef of that name)" : "";
        parent = r.enterParent(written, written.inherit, written.inheritWhere, "model", find, note);
        if (parent) resolveModel(r, decls, *parent);
    }
    ModelDecl& model = r.decls()[i];
    if (parent) {
        mergeModel(model, r.decls()[*parent], r.diagnostics());
    } else {
        for (const ModelRemove& remove : model.removes)
            r.diagnostics().push_back(diagnostic(Severity::Warning, model.file, remove.where,
                                                 "remove '" + remove.alias +
                                                     "' has nothing to remove: the model inherits no anims"));
    }
    model.inherit.clear();
    model.removes.clear();
    r.end(i);
}

}  // namespace

void DefCollection::add(const DefFile& file, std::vector<Diagnostic>& diagnostics) {
    for (const EntityDef& def : file.entityDefs) add(def, diagnostics);
    for (const ModelDecl& model : file.models) add(model, diagnostics);
}

void DefCollection::add(EntityDef decl, std::vector<Diagnostic>& diagnostics) {
    if (auto it = entityIndex_.find(decl.name); it != entityIndex_.end()) {
        const EntityDef& first = entityDefs_[it->second];
        diagnostics.push_back(diagnostic(Severity::Warning, decl.file, decl.where,
                                         "entityDef '" + decl.name + "' is defined again; the definition in " +
                                             first.file + " at line " + std::to_string(first.where.line) + " is used"));
        return;
    }
    entityIndex_.emplace(decl.name, entityDefs_.size());
    entityDefs_.push_back(std::move(decl));
}

void DefCollection::add(ModelDecl decl, std::vector<Diagnostic>& diagnostics) {
    if (auto it = modelIndex_.find(decl.name); it != modelIndex_.end()) {
        const ModelDecl& first = models_[it->second];
        diagnostics.push_back(diagnostic(Severity::Warning, decl.file, decl.where,
                                         "model '" + decl.name + "' is defined again; the definition in " + first.file +
                                             " at line " + std::to_string(first.where.line) + " is used"));
        return;
    }
    modelIndex_.emplace(decl.name, models_.size());
    models_.push_back(std::move(decl));
}

const EntityDef* DefCollection::findEntityDef(std::string_view name) const {
    auto it = entityIndex_.find(canonicalDeclName(name));
    return it == entityIndex_.end() ? nullptr : &entityDefs_[it->second];
}

const ModelDecl* DefCollection::findModel(std::string_view name) const {
    auto it = modelIndex_.find(canonicalDeclName(name));
    return it == modelIndex_.end() ? nullptr : &models_[it->second];
}

bool ResolvedDefs::ok() const {
    return std::none_of(diagnostics.begin(), diagnostics.end(),
                        [](const Diagnostic& d) { return d.severity == Severity::Error; });
}

std::string ResolvedDefs::formatDiagnostics() const {
    std::string out;
    for (const Diagnostic& d : diagnostics) out += d.format() + '\n';
    return out;
}

ResolvedDefs resolveDefInheritance(const DefCollection& decls) {
    ResolvedDefs result;
    Resolver<EntityDef> entities(decls.entityDefs(), result.diagnostics);
    for (std::size_t i = 0; i < decls.entityDefs().size(); ++i) resolveEntity(entities, decls, i);
    Resolver<ModelDecl> models(decls.models(), result.diagnostics);
    for (std::size_t i = 0; i < decls.models().size(); ++i) resolveModel(models, decls, i);

    // Names are unique in `decls`, so adding cannot warn.
    std::vector<Diagnostic> none;
    for (EntityDef& def : entities.decls()) result.decls.add(std::move(def), none);
    for (ModelDecl& model : models.decls()) result.decls.add(std::move(model), none);
    return result;
}

}  // namespace af
