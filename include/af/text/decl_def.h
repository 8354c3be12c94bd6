#pragma once
// `.def` decl files (docs/formats.md §1.1, §2.4, §2.5): the `entityDef` and `model` decls kept
// as plain data, every other decl kind skipped, and inheritance resolved as a separate step.
//
// A file is a sequence of `TYPE NAME { ... }`. The type keyword is case-insensitive; a name
// directly followed by `{` is an entityDef (the default type of def/ folders). Any other type
// (`export`, `material`, `table`, `skin`, `sound`, `particle`, a type we have never heard of) is
// skipped by brace matching and listed in DefFile::skipped, so a real mod folder loads. Errors
// are true syntax errors only: unbalanced braces, an entityDef key that is not a quoted string,
// the end of the file inside a block, a malformed model decl item. After an error the parser
// skips to the end of that decl and goes on with the next one.

#include "af/text/diagnostics.h"
#include "af/types.h"

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace af {

struct DefKeyValue {
    std::string key;
    std::string value;    // the token's text: strings without quotes, numbers as spelled
    SourceLocation where; // of the key that set the value, in the file of the decl that wrote it
    std::string inheritedFrom;  // after resolveDefInheritance: the decl that wrote it; empty if own
};

// `entityDef NAME { "key" "value" ... }` as written. A repeated key (compared ignoring case, as
// idDict does) is a warning; it keeps its first spelling and position in the list and takes the
// later value, as idDict::Set does. `inherit` keys stay here; resolveDefInheritance acts on them.
struct EntityDef {
    std::string name;         // canonical (canonicalDeclName), for lookup
    std::string writtenName;  // as the file spelled it
    std::string file;
    SourceLocation where;     // of the name
    std::vector<DefKeyValue> keyValues;

    // The key/value for `key`, ignoring case, or nullptr.
    const DefKeyValue* find(std::string_view key) const;
    // The value for `key`, or `fallback` when the key is not set.
    std::string valueOr(std::string_view key, std::string_view fallback = {}) const;
};

// `anim ALIAS FILE [, FILE ...] [ { frame commands } ]`. The frame-command block is skipped.
struct ModelAnim {
    std::string alias;                // as written; case-sensitive, "walk2" is variant 2 of "walk"
    std::vector<std::string> files;
    bool hasFrameCommands = false;
    SourceLocation where;             // of the alias
};

// `channel NAME ( joint list )`; the list is kept in containedJoints syntax ("*Waist -*Neck").
struct ModelChannel {
    std::string name;
    std::string joints;
    SourceLocation where;
};

struct ModelRemove {
    std::string alias;
    SourceLocation where;
};

// `model NAME { ... }` as written. The keys are case-sensitive, as in Doom. Empty strings and an
// empty offset mean "not set here" (so that inheritance can tell what to take from the parent).
struct ModelDecl {
    std::string name;         // canonical, for lookup
    std::string writtenName;
    std::string file;
    SourceLocation where;     // of the name
    std::string inherit;      // the parent's name as written; empty for none
    SourceLocation inheritWhere;
    std::string mesh;         // the .md5mesh path
    SourceLocation meshWhere;
    std::string skin;
    std::optional<Real3> offset;  // added to the root joint of the AF pose (docs/formats.md §2.3)
    std::vector<ModelChannel> channels;
    std::vector<ModelAnim> anims;
    std::vector<ModelRemove> removes;

    // The anim with exactly this alias (case-sensitive), or nullptr; `af_pose` is the AF's pose.
    const ModelAnim* findAnim(std::string_view alias) const;
};

// A decl of another kind that was skipped.
struct SkippedDecl {
    std::string type;   // as written
    std::string name;
    SourceLocation where;  // of the type keyword
};

struct DefFile {
    std::string path;
    std::vector<EntityDef> entityDefs;  // in file order; a repeated name keeps the first (Doom)
    std::vector<ModelDecl> models;
    std::vector<SkippedDecl> skipped;
};

struct DefParseResult {
    DefFile file;
    Diagnostics diagnostics;

    bool ok() const { return !diagnostics.hasErrors(); }
};

// Parses `text`; `fileName` is used in diagnostics and recorded in each decl.
DefParseResult parseDef(std::string_view text, std::string fileName);
// Reads and parses a file; a file that cannot be read is an error diagnostic.
DefParseResult loadDefFile(const std::string& path);

// The decls of any number of .def files, found by name. entityDefs and models are separate
// namespaces (a model and an entityDef often share a name). Lookups canonicalise the name, so
// "Char_Foo" and "char_foo.def" find "char_foo".
class DefCollection {
public:
    // Adds a file's decls. A name that is already there keeps its first definition, as Doom's
    // decl manager does; the repeat is a warning appended to `diagnostics`.
    void add(const DefFile& file, std::vector<Diagnostic>& diagnostics);
    void add(EntityDef decl, std::vector<Diagnostic>& diagnostics);
    void add(ModelDecl decl, std::vector<Diagnostic>& diagnostics);

    const EntityDef* findEntityDef(std::string_view name) const;
    const ModelDecl* findModel(std::string_view name) const;

    const std::vector<EntityDef>& entityDefs() const { return entityDefs_; }
    const std::vector<ModelDecl>& models() const { return models_; }

private:
    std::vector<EntityDef> entityDefs_;
    std::vector<ModelDecl> models_;
    std::map<std::string, std::size_t, std::less<>> entityIndex_;
    std::map<std::string, std::size_t, std::less<>> modelIndex_;
};

struct ResolvedDefs {
    DefCollection decls;
    std::vector<Diagnostic> diagnostics;  // each with its own file

    bool ok() const;
    std::string formatDiagnostics() const;
};

// Resolves inheritance in every decl, as Doom does after parsing (docs/formats.md §2.4, §2.5):
//  * entityDef: `classname` is set to the decl's canonical name; every key starting with
//    "inherit" (ignoring case) names a parent, in key order; the keys are removed and each
//    resolved parent fills in the keys the decl does not set;
//  * model: the resolved parent supplies mesh, skin, offset, channels and anims; the decl's own
//    mesh/skin/offset replace them, its channels replace same-named ones, its `remove`s drop
//    inherited anims (by alias, or by alias without its number suffix), and its anims replace
//    same-alias inherited ones. Doom applies `inherit` where it is written; every shipped decl
//    writes it first, and we treat it as written first.
// An unknown parent or an inheritance cycle is an error at the inheriting key; the decl keeps
// what it has without that parent. A `remove` that matches no inherited anim is a warning.
ResolvedDefs resolveDefInheritance(const DefCollection& decls);

}  // namespace af
