// The figure editor's commands (docs/console-editing.md): editBody and editConstraint set one key
// of a body or constraint of an entity's .af decl, key and value spelled as in the file; every
// entity of that decl respawns at its spawn placement with the new figure; saveAF writes the decl
// back through the canonical writer and a temporary file; respawnRagdolls puts every figure back
// at its spawn pose; checkFigure prints the figure checks.
//
// An edit is checked as the file would be: the decl is written, the key's line added at the end
// of the item's block, and the text parsed and the figure built again. So a value the .af parser
// or the figure builder refuses is refused here in their words, in one line, and nothing changes.

#include "console/session_state.h"

#include "af/text/af_parser.h"
#include "af/text/af_writer.h"
#include "af/text/strings.h"

#include <algorithm>
#include <cctype>
#include <charconv>

namespace af::console {

namespace {

using State = Session::State;

// The keys a body block and each kind of constraint block may hold (docs/formats.md §1.6, §1.7),
// for tab completion; the parser is what decides.
const std::vector<std::string> kBodyKeys = {"joint",    "mod",          "model",    "origin",        "angles",
                                            "density",  "inertiaScale", "friction", "contents",      "clipMask",
                                            "selfCollision", "containedJoints", "frictionDirection", "contactMotorDirection"};

std::vector<std::string> constraintKeys(ConstraintType type) {
    std::vector<std::string> keys = {"body1", "body2"};
    const auto add = [&keys](std::initializer_list<const char*> more) { keys.insert(keys.end(), more.begin(), more.end()); };
    switch (type) {
    case ConstraintType::Fixed: break;
    case ConstraintType::BallAndSocket: add({"anchor", "friction", "coneLimit", "pyramidLimit"}); break;
    case ConstraintType::Universal: add({"anchor", "shafts", "friction", "coneLimit", "pyramidLimit"}); break;
    case ConstraintType::Hinge: add({"anchor", "axis", "friction", "limit"}); break;
    case ConstraintType::Slider: add({"axis", "friction"}); break;
    case ConstraintType::Spring:
        add({"anchor1", "anchor2", "friction", "stretch", "compress", "damping", "restLength", "minLength", "maxLength"});
        break;
    }
    return keys;
}

bool isNumber(std::string_view word) {
    double v = 0;
    const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), v);
    return ec == std::errc() && end == word.data() + word.size();
}

// The console strips double quotes, and the .af file wants them around names. They go back around
// the words that are names in the .af grammar: the value of joint, body1 and body2, the whole value
// of containedJoints, and the names inside joint( ), bonecenter( ), bonedir( ) and custom( ).
// Every other word (numbers, `,`, `(`, keywords such as box or corpse) goes as it is.
std::string afValueText(std::string_view key, const std::vector<std::string>& words) {
    std::string joined;
    for (const std::string& w : words) joined += (joined.empty() ? "" : " ") + w;
    if (equalsIgnoreCase(key, "containedJoints")) return "\"" + joined + "\"";
    const bool nameValue = equalsIgnoreCase(key, "joint") || equalsIgnoreCase(key, "body1") || equalsIgnoreCase(key, "body2");
    std::string out, previous;
    std::vector<std::string> opened;  // the word before each open `(`
    bool first = true;
    for (std::size_t i = 0; i < joined.size();) {
        const char c = joined[i];
        if (std::isspace(static_cast<unsigned char>(c))) {
            ++i;
            continue;
        }
        std::string token;
        if (c == '(' || c == ')' || c == ',') {
            token = std::string(1, c);
            ++i;
            if (c == '(') opened.push_back(previous);
            else if (c == ')' && !opened.empty()) opened.pop_back();
        } else {
            std::size_t end = i;
            while (end < joined.size() && !std::isspace(static_cast<unsigned char>(joined[end])) && joined[end] != '(' &&
                   joined[end] != ')' && joined[end] != ',')
                ++end;
            token = joined.substr(i, end - i);
            i = end;
            std::string_view opener = opened.empty() ? std::string_view() : std::string_view(opened.back());
            if (!opener.empty() && opener.front() == '-') opener.remove_prefix(1);
            const bool inNames = opener == "joint" || opener == "bonecenter" || opener == "bonedir" || opener == "custom";
            if (!isNumber(token) && ((first && nameValue) || inNames)) token = "\"" + token + "\"";
        }
        out += (out.empty() ? "" : " ") + token;
        previous = token;
        first = false;
    }
    return out;
}

std::string firstError(const std::vector<Diagnostic>& diagnostics) {
    for (const Diagnostic& d : diagnostics)
        if (d.severity == Severity::Error) return d.message;
    return "refused";
}

// What editBody and editConstraint share: find the item, add the key's line, parse, check, build,
// and only then take the new decl and respawn.
Status editItem(State& s, bool body, const CommandArgs& a, const Output& out) {
    const std::string command = a.argv(0);
    Entity* e = s.find(a.argv(1));
    if (!e) return Status::failure(command + ": no entity named " + a.argv(1));
    const AFResources r = s.resources(e->entityDef);
    if (!r.ok()) return Status::failure(command + ": " + e->name + ": " + firstError(r.diagnostics));
    const DeclAF& decl = r.figure->decl;
    const std::string& itemName = a.argv(2);
    std::string header;
    int index = -1;
    if (body) {
        for (std::size_t i = 0; i < decl.bodies.size() && index < 0; ++i)
            if (equalsIgnoreCase(decl.bodies[i].name, itemName)) index = int(i);
        if (index < 0) return Status::failure(command + ": " + e->name + " has no body " + itemName);
        header = "body \"" + decl.bodies[std::size_t(index)].name + "\" {";
    } else {
        for (std::size_t i = 0; i < decl.constraints.size() && index < 0; ++i)
            if (equalsIgnoreCase(decl.constraints[i].name, itemName)) index = int(i);
        if (index < 0) return Status::failure(command + ": " + e->name + " has no constraint " + itemName);
        const AFConstraint& c = decl.constraints[std::size_t(index)];
        header = std::string(toString(c.type)) + " \"" + c.name + "\" {";
    }
    const std::string& key = a.argv(3);
    if (key.empty() || !std::all_of(key.begin(), key.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)); }))
        return Status::failure(command + ": the key must be one word of the .af file, found '" + key + "'");
    const std::vector<std::string> words(a.words().begin() + 4, a.words().end());
    const std::string line = key + " " + afValueText(key, words);
    std::string typed = key;  // as the user wrote it, for messages
    for (const std::string& w : words) typed += " " + w;
    const std::string label = command + ": " + e->name + " " + itemName + ": " + typed + ": ";

    // The key's line last in the item's block of the canonical text: the parser takes the last
    // value a key is given.
    std::string text = writeDecl(decl);
    const std::size_t start = text.find("\n" + header + "\n");
    const std::size_t close = start == std::string::npos ? start : text.find("\n}", start + 1);
    if (close == std::string::npos) return Status::failure(label + "its block is not found in the written decl");
    text.insert(close, "\n\t" + line);
    const AFParseResult parsed = parseAF(text, r.figure->file);
    if (!parsed.ok()) return Status::failure(label + firstError(parsed.diagnostics.all()));

    // The value must stay inside its block: every other part of the decl reads as before.
    const DeclAF* next = parsed.file.decls.size() == 1 ? &parsed.file.decls[0] : nullptr;
    bool same = next && next->name == decl.name && next->settings == decl.settings && next->bodies.size() == decl.bodies.size() &&
                next->constraints.size() == decl.constraints.size();
    for (std::size_t i = 0; same && i < decl.bodies.size(); ++i)
        same = (body && int(i) == index) ? next->bodies[i].name == decl.bodies[i].name : next->bodies[i] == decl.bodies[i];
    for (std::size_t i = 0; same && i < decl.constraints.size(); ++i)
        same = (!body && int(i) == index) ? next->constraints[i].name == decl.constraints[i].name
                                          : next->constraints[i] == decl.constraints[i];
    if (!same) return Status::failure(label + "the value reaches beyond the " + (body ? "body" : "constraint"));

    AFResources candidate = r;
    candidate.figure = std::make_shared<const FigureEntry>(FigureEntry{*next, r.figure->file});
    const FigureResult built = buildFigure(candidate);
    if (!built.ok()) return Status::failure(label + firstError(built.diagnostics));

    // The warnings the edit brings (the figure checks, a joint the skeleton lacks, ...): those of
    // the new build that the old one did not give.
    std::vector<std::string> before;
    for (const Diagnostic& d : buildFigure(r).diagnostics) before.push_back(d.message);
    s.editedDecls[decl.name] = *next;
    const int respawned = s.respawn(false, out);
    out.info("edited " + e->name + " " + itemName + ": " + typed + " (" + std::to_string(respawned) + " ragdoll" +
             (respawned == 1 ? "" : "s") + " respawned)");
    for (const Diagnostic& d : built.diagnostics)
        if (d.severity == Severity::Warning && std::find(before.begin(), before.end(), d.message) == before.end())
            out.info("warning: " + d.message);
    return Status::success();
}

// The decl into its .af file (or FILE): the file is read, the decl of that name replaced (or
// added), and the whole file written in the canonical layout through a temporary file.
Status saveAF(State& s, const CommandArgs& a, const Output& out) {
    const Entity* e = s.find(a.argv(1));
    if (!e) return Status::failure("saveAF: no entity named " + a.argv(1));
    const AFResources r = s.resources(e->entityDef);
    if (!r.ok()) return Status::failure("saveAF: " + e->name + ": " + firstError(r.diagnostics));
    const DeclAF& decl = r.figure->decl;
    const std::filesystem::path target = a.argc() == 3 ? std::filesystem::path(a.argv(2)) : std::filesystem::path(r.figure->file);
    AFFile file;
    std::error_code ec;
    if (std::filesystem::exists(target, ec)) {
        AFParseResult read = loadAFFile(target.string());
        if (!read.ok())
            return Status::failure("saveAF: " + target.string() + " does not read cleanly, so it is not overwritten: " +
                                   firstError(read.diagnostics.all()));
        file = std::move(read.file);
    }
    const auto same = std::find_if(file.decls.begin(), file.decls.end(), [&](const DeclAF& d) { return equalsIgnoreCase(d.name, decl.name); });
    if (same != file.decls.end()) *same = decl;
    else file.decls.push_back(decl);
    const WriteResult written = writeFileAtomically(target, writeAFFile(file), s.writeHook);
    if (!written.ok()) return Status::failure("saveAF: " + written.error);
    out.info("saved articulatedFigure " + decl.name + " to " + target.string());
    return Status::success();
}

Status checkFigure(State& s, const CommandArgs& a, const Output& out) {
    const Entity* e = s.find(a.argv(1));
    if (!e) return Status::failure("checkFigure: no entity named " + a.argv(1));
    const Figure& figure = s.world.definition(e->figure);
    const std::vector<FigureWarning> warnings = figureWarnings(figure);
    for (const FigureWarning& w : warnings) out.info("warning: " + w.message);
    out.info(e->name + ": " + std::to_string(warnings.size()) + " warning" + (warnings.size() == 1 ? "" : "s"));
    return Status::success();
}

}  // namespace

void registerEditCommands(State& s, CommandSystem& console) {
    const auto entityNames = [&s] {
        std::vector<std::string> names;
        for (const Entity& e : s.entities) names.push_back(e.name);
        return names;
    };
    // ENTITY, then its bodies or constraints, then the keys of that body or constraint.
    const auto completeItem = [&s, entityNames](bool body) {
        return [&s, entityNames, body](const CommandArgs& typed, std::string_view) {
            std::vector<std::string> out;
            if (typed.argc() == 1) return entityNames();
            const Entity* e = s.find(typed.argv(1));
            if (!e) return out;
            const DeclAF& d = e->source.decl;
            if (typed.argc() == 2) {
                if (body)
                    for (const AFBody& b : d.bodies) out.push_back(b.name);
                else
                    for (const AFConstraint& c : d.constraints) out.push_back(c.name);
            } else if (typed.argc() == 3) {
                if (body) return kBodyKeys;
                if (const AFConstraint* c = d.findConstraint(typed.argv(2))) return constraintKeys(c->type);
            }
            return out;
        };
    };
    console.addCommand({"editBody", "ENTITY BODY KEY VALUE...",
                        "set a key of a body of the entity's .af decl, as written in the file (model, origin, density, friction, "
                        "...); every entity of that decl respawns with it",
                        4, {}, [&s](const CommandArgs& a, const Output& out) { return editItem(s, true, a, out); }, completeItem(true)});
    console.addCommand({"editConstraint", "ENTITY CONSTRAINT KEY VALUE...",
                        "set a key of a constraint of the entity's .af decl, as written in the file (anchor, axis, limit, "
                        "coneLimit, friction, ...); every entity of that decl respawns with it",
                        4, {}, [&s](const CommandArgs& a, const Output& out) { return editItem(s, false, a, out); }, completeItem(false)});
    const auto completeEntity = [entityNames](const CommandArgs& typed, std::string_view) {
        return typed.argc() == 1 ? entityNames() : std::vector<std::string>{};
    };
    console.addCommand({"saveAF", "ENTITY [FILE]", "write the entity's .af decl, edits included, into its .af file (or FILE)", 1, 2,
                        [&s](const CommandArgs& a, const Output& out) { return saveAF(s, a, out); }, completeEntity});
    console.addCommand({"checkFigure", "ENTITY", "print the warnings about the entity's figure (mass ratios, inertia, overlaps)", 1, 1,
                        [&s](const CommandArgs& a, const Output& out) { return checkFigure(s, a, out); }, completeEntity});
    console.addCommand({"respawnRagdolls", "", "put every ragdoll back at its spawn placement, in its spawn pose", 0, 0,
                        [&s](const CommandArgs&, const Output& out) {
                            s.world.clearDrag();
                            const int n = s.respawn(true, out);
                            out.info("respawned " + std::to_string(n) + " ragdoll" + (n == 1 ? "" : "s"));
                            return Status::success();
                        },
                        {}});
}

}  // namespace af::console
