#pragma once
// Console variables: named, typed settings that scripts and the console read and change, as
// Doom's cvars are (docs/doom-physics.md §4.13). A value is checked before it is taken: text
// that does not parse, a non-finite number or one outside the cvar's range is refused with a
// message and the cvar keeps its value (docs/architecture.md, "never a silent default"). Names
// are found ignoring case, as Doom finds them. The owner of a setting learns of a change
// through the cvar's callback and applies it; nothing here knows what a cvar means.

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace af::console {

// The outcome of a console operation: success, or the message saying why it was refused.
class Status {
public:
    static Status success() { return Status(); }
    static Status failure(std::string message) { return Status(std::move(message)); }

    bool ok() const { return !message_.has_value(); }
    const std::string& message() const;  // empty when ok()

private:
    Status() = default;
    explicit Status(std::string message) : message_(std::move(message)) {}
    std::optional<std::string> message_;
};

// Names of cvars and commands: letters, digits and `_`, not starting with a digit.
bool isConsoleName(std::string_view name);

enum class CVarType { Bool, Int, Real, String };

// The variant's alternatives are in CVarType's order.
using CVarValue = std::variant<bool, std::int64_t, double, std::string>;

enum class CVarFlags : unsigned {
    None = 0,
    Archive = 1,     // written by CVarSystem::archive (Doom's CVAR_ARCHIVE; `seta` adds it)
    ReadOnly = 2,    // only the owner changes it (CVarSystem::Access::Owner)
    Simulation = 4,  // changes the simulation, as Doom's CVAR_CHEAT ones do; shown in listings
};
constexpr CVarFlags operator|(CVarFlags a, CVarFlags b) { return CVarFlags(unsigned(a) | unsigned(b)); }
constexpr bool hasFlag(CVarFlags set, CVarFlags flag) { return (unsigned(set) & unsigned(flag)) != 0; }

// Bounds of a number cvar, inclusive; an absent bound is no bound.
struct CVarRange {
    std::optional<double> min;
    std::optional<double> max;
};

class CVar;

// What registering a cvar takes. The type is the default value's; make one with the helpers
// below and add a callback if the owner applies the value.
struct CVarDefinition {
    std::string name;
    CVarValue defaultValue;
    std::string help;
    CVarRange range;                         // Int and Real only
    std::vector<std::string> allowedValues;  // String only; empty allows any
    CVarFlags flags = CVarFlags::None;
    std::function<void(const CVar&)> onChange;  // after every change of value
};

CVarDefinition boolCVar(std::string name, bool value, std::string help, CVarFlags flags = CVarFlags::None);
CVarDefinition intCVar(std::string name, std::int64_t value, CVarRange range, std::string help,
                       CVarFlags flags = CVarFlags::None);
CVarDefinition realCVar(std::string name, double value, CVarRange range, std::string help,
                        CVarFlags flags = CVarFlags::None);
CVarDefinition stringCVar(std::string name, std::string value, std::string help,
                          std::vector<std::string> allowedValues = {}, CVarFlags flags = CVarFlags::None);

// A registered cvar. Read-only to everyone: changes go through CVarSystem, which checks them.
class CVar {
public:
    // A bad definition is a programming error and throws std::invalid_argument: a name not
    // made of letters, digits and `_`, a default outside the range or not allowed, a
    // non-finite number, a String holding a `"` or a line break (archive could not write it).
    explicit CVar(CVarDefinition definition);

    const std::string& name() const { return def_.name; }
    CVarType type() const { return CVarType(value_.index()); }
    const std::string& help() const { return def_.help; }
    CVarFlags flags() const { return def_.flags; }
    const CVarRange& range() const { return def_.range; }
    const std::vector<std::string>& allowedValues() const { return def_.allowedValues; }

    const CVarValue& value() const { return value_; }
    const CVarValue& defaultValue() const { return def_.defaultValue; }
    // The value as a number: a Bool is 0 or 1. asInt throws std::logic_error for a Real or a
    // String, asBool and asReal for a String.
    bool asBool() const { return asReal() != 0; }
    std::int64_t asInt() const;
    double asReal() const;
    // Throws std::logic_error unless the cvar is a String.
    const std::string& asString() const;

    // The value as typed: "1"/"0" for a Bool, the shortest text that reads back for a Real.
    std::string text() const;
    std::string defaultText() const;
    // "real in [0, 10000]", "string: tree or exact", …
    std::string describeType() const;

    // The text as a value of this cvar's type, or why it is not one.
    std::variant<CVarValue, std::string> parse(std::string_view text) const;

private:
    friend class CVarSystem;
    CVarDefinition def_;
    CVarValue value_;
};

// Every cvar of a console, by name ignoring case.
class CVarSystem {
public:
    // Who asks for a change: the user (console, scripts) may not change a ReadOnly cvar.
    enum class Access { User, Owner };

    // Registers a cvar at its default; throws std::invalid_argument when the name is taken or
    // the definition is bad (CVar's constructor).
    CVar& add(CVarDefinition definition);

    CVar* find(std::string_view name);
    const CVar* find(std::string_view name) const;

    // Sets from text; refused with a message (and the cvar unchanged) when the text is not a
    // value of the cvar's type and range. Setting the value it has is no change.
    Status set(std::string_view name, std::string_view text, Access access = Access::User);

    // Doom's toggle: no values flips a Bool and turns a number between 0 and 1; one value turns
    // a number (or Bool) between 0 and it; two or more cycle through them, going to the first
    // when the current value is none of them.
    Status toggle(std::string_view name, const std::vector<std::string>& values, Access access = Access::User);

    Status reset(std::string_view name, Access access = Access::User);

    // The cvars whose names start with `prefix` (ignoring case), sorted by name.
    std::vector<const CVar*> list(std::string_view prefix = {}) const;

    // Adds Archive to a cvar's flags (`seta`).
    void markArchived(CVar& cvar) { cvar.def_.flags = cvar.def_.flags | CVarFlags::Archive; }

    // `seta NAME "VALUE"` for every Archive cvar, one a line, sorted: a script that restores
    // them.
    std::string archive() const;

private:
    Status assign(CVar& cvar, CVarValue value, Access access);

    std::map<std::string, CVar> cvars_;  // by lower-case name: sorted, and nodes stay put
};

}  // namespace af::console
