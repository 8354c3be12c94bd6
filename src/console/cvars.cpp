// Cvars and their checks (cvars.h). Values are parsed from text in one place, CVar::parse, so a
// script, the console, toggle and the owner's updates are refused for the same reasons.

#include "console/cvars.h"
#include "console/console_text.h"

#include "af/text/strings.h"

#include <charconv>
#include <cmath>
#include <stdexcept>

namespace af::console {

namespace {

// The shortest text that reads back as the same double ("1066", "0.5", "1e-12").
std::string formatReal(double v) {
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
    return std::string(buffer, result.ptr);
}


// from_chars takes no leading `+`; a typed `+5` is still five.
std::string_view withoutPlus(std::string_view text) {
    return text.size() > 1 && text[0] == '+' && text[1] != '-' ? text.substr(1) : text;
}

std::string describeRange(const CVarRange& range) {
    if (range.min && range.max) return " in [" + formatReal(*range.min) + ", " + formatReal(*range.max) + "]";
    if (range.min) return ", at least " + formatReal(*range.min);
    if (range.max) return ", at most " + formatReal(*range.max);
    return "";
}

// Why `number` is outside `range`, or empty.
std::string rangeProblem(const std::string& name, double number, const CVarRange& range) {
    if (range.min && number < *range.min)
        return quoted(name) + " must be at least " + formatReal(*range.min) + ", not " + formatReal(number);
    if (range.max && number > *range.max)
        return quoted(name) + " must be at most " + formatReal(*range.max) + ", not " + formatReal(number);
    return {};
}

std::string joinAllowed(const std::vector<std::string>& allowed) {
    std::string out;
    for (const std::string& value : allowed) out += (out.empty() ? "" : ", ") + value;
    return out;
}

double numberOf(const CVarValue& value) {
    switch (CVarType(value.index())) {
    case CVarType::Bool: return std::get<bool>(value) ? 1.0 : 0.0;
    case CVarType::Int: return double(std::get<std::int64_t>(value));
    case CVarType::Real: return std::get<double>(value);
    case CVarType::String: break;
    }
    throw std::logic_error("a string cvar has no number");
}

std::string textOf(const CVarValue& value) {
    switch (CVarType(value.index())) {
    case CVarType::Bool: return std::get<bool>(value) ? "1" : "0";
    case CVarType::Int: return std::to_string(std::get<std::int64_t>(value));
    case CVarType::Real: return formatReal(std::get<double>(value));
    case CVarType::String: return std::get<std::string>(value);
    }
    return {};
}

// Doom's toggle compares the typed values with the current one ignoring case.
bool sameValue(const CVarValue& a, const CVarValue& b) {
    if (a.index() != b.index()) return false;
    if (const auto* text = std::get_if<std::string>(&a)) return equalsIgnoreCase(*text, std::get<std::string>(b));
    return a == b;
}

}  // namespace

bool isConsoleName(std::string_view name) {
    if (name.empty() || (name[0] >= '0' && name[0] <= '9')) return false;
    for (char c : name)
        if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_')) return false;
    return true;
}

const std::string& Status::message() const {
    static const std::string kNone;
    return message_ ? *message_ : kNone;
}

CVarDefinition boolCVar(std::string name, bool value, std::string help, CVarFlags flags) {
    return {std::move(name), value, std::move(help), {}, {}, flags, {}};
}

CVarDefinition intCVar(std::string name, std::int64_t value, CVarRange range, std::string help, CVarFlags flags) {
    return {std::move(name), value, std::move(help), range, {}, flags, {}};
}

CVarDefinition realCVar(std::string name, double value, CVarRange range, std::string help, CVarFlags flags) {
    return {std::move(name), value, std::move(help), range, {}, flags, {}};
}

CVarDefinition stringCVar(std::string name, std::string value, std::string help,
                          std::vector<std::string> allowedValues, CVarFlags flags) {
    return {std::move(name), std::move(value), std::move(help), {}, std::move(allowedValues), flags, {}};
}

CVar::CVar(CVarDefinition definition) : def_(std::move(definition)), value_(def_.defaultValue) {
    if (!isConsoleName(def_.name))
        throw std::invalid_argument("cvar name " + quoted(def_.name) + " is not letters, digits and '_'");
    if (def_.range.min && def_.range.max && *def_.range.min > *def_.range.max)
        throw std::invalid_argument("cvar " + quoted(def_.name) + " has an empty range");
    if (type() == CVarType::Real && !std::isfinite(std::get<double>(value_)))
        throw std::invalid_argument("cvar " + quoted(def_.name) + " has a non-finite default");
    // The default must survive its own check, so reset can never be refused for its value.
    auto parsed = parse(textOf(value_));
    if (const auto* problem = std::get_if<std::string>(&parsed))
        throw std::invalid_argument("default of cvar " + quoted(def_.name) + ": " + *problem);
    def_.defaultValue = value_ = std::get<CVarValue>(std::move(parsed));  // an allowed value as spelt in the list
}

std::int64_t CVar::asInt() const {
    if (type() == CVarType::Bool) return std::get<bool>(value_) ? 1 : 0;
    if (type() != CVarType::Int) throw std::logic_error("cvar " + quoted(name()) + " is not an integer");
    return std::get<std::int64_t>(value_);
}

double CVar::asReal() const { return numberOf(value_); }

const std::string& CVar::asString() const {
    if (type() != CVarType::String) throw std::logic_error("cvar " + quoted(name()) + " is not a string");
    return std::get<std::string>(value_);
}

std::string CVar::text() const { return textOf(value_); }

std::string CVar::defaultText() const { return textOf(def_.defaultValue); }

std::string CVar::describeType() const {
    switch (type()) {
    case CVarType::Bool: return "bool (0 or 1)";
    case CVarType::Int: return "integer" + describeRange(def_.range);
    case CVarType::Real: return "real" + describeRange(def_.range);
    case CVarType::String: return def_.allowedValues.empty() ? "string" : "string: " + joinAllowed(def_.allowedValues);
    }
    return {};
}

std::variant<CVarValue, std::string> CVar::parse(std::string_view text) const {
    const std::string& n = name();
    switch (type()) {
    case CVarType::Bool:
        if (text == "1" || equalsIgnoreCase(text, "true")) return CVarValue(true);
        if (text == "0" || equalsIgnoreCase(text, "false")) return CVarValue(false);
        return quoted(n) + " needs 0, 1, true or false, not " + quoted(text);
    case CVarType::Int: {
        const std::string_view digits = withoutPlus(text);
        std::int64_t value = 0;
        const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
        if (error == std::errc::result_out_of_range) return quoted(n) + " cannot hold " + quoted(text);
        if (error != std::errc() || end != digits.data() + digits.size() || digits.empty())
            return quoted(n) + " needs an integer, not " + quoted(text);
        if (std::string problem = rangeProblem(n, double(value), def_.range); !problem.empty()) return problem;
        return CVarValue(value);
    }
    case CVarType::Real: {
        const std::string_view digits = withoutPlus(text);
        double value = 0;
        const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
        const bool whole = end == digits.data() + digits.size() && !digits.empty();
        if (error == std::errc::result_out_of_range && whole)
            return quoted(n) + " needs a finite number, not " + quoted(text);
        if (error != std::errc() || !whole) return quoted(n) + " needs a number, not " + quoted(text);
        if (!std::isfinite(value)) return quoted(n) + " needs a finite number, not " + quoted(text);
        if (std::string problem = rangeProblem(n, value, def_.range); !problem.empty()) return problem;
        return CVarValue(value);
    }
    case CVarType::String:
        if (text.find_first_of("\"\r\n") != std::string_view::npos)
            return quoted(n) + " cannot hold a double quote or a line break";
        if (def_.allowedValues.empty()) return CVarValue(std::string(text));
        for (const std::string& allowed : def_.allowedValues)
            if (equalsIgnoreCase(allowed, text)) return CVarValue(allowed);
        return quoted(n) + " must be one of " + joinAllowed(def_.allowedValues) + ", not " + quoted(text);
    }
    return std::string("unknown cvar type");
}

CVar& CVarSystem::add(CVarDefinition definition) {
    std::string key = toLower(definition.name);
    if (cvars_.contains(key)) throw std::invalid_argument("cvar " + quoted(definition.name) + " is already registered");
    return cvars_.emplace(std::move(key), CVar(std::move(definition))).first->second;
}

CVar* CVarSystem::find(std::string_view name) {
    const auto it = cvars_.find(toLower(name));
    return it == cvars_.end() ? nullptr : &it->second;
}

const CVar* CVarSystem::find(std::string_view name) const { return const_cast<CVarSystem*>(this)->find(name); }

Status CVarSystem::set(std::string_view name, std::string_view text, Access access) {
    CVar* cvar = find(name);
    if (!cvar) return Status::failure("unknown cvar " + quoted(name));
    auto parsed = cvar->parse(text);
    if (auto* problem = std::get_if<std::string>(&parsed)) return Status::failure(std::move(*problem));
    return assign(*cvar, std::get<CVarValue>(std::move(parsed)), access);
}

Status CVarSystem::toggle(std::string_view name, const std::vector<std::string>& values, Access access) {
    CVar* cvar = find(name);
    if (!cvar) return Status::failure("unknown cvar " + quoted(name));
    if (values.size() >= 2) {
        std::size_t next = 0;
        for (std::size_t i = 0; i < values.size(); ++i) {
            const auto parsed = cvar->parse(values[i]);
            const auto* value = std::get_if<CVarValue>(&parsed);
            if (value && sameValue(*value, cvar->value())) {
                next = (i + 1) % values.size();
                break;
            }
        }
        return set(name, values[next], access);
    }
    if (cvar->type() == CVarType::String)
        return Status::failure(quoted(cvar->name()) + " is a string: toggle it through two or more values");
    if (cvar->type() == CVarType::Bool && values.empty()) return assign(*cvar, !std::get<bool>(cvar->value()), access);
    const bool isZero = cvar->asReal() == 0;
    return set(name, isZero ? (values.empty() ? "1" : values[0]) : "0", access);
}

Status CVarSystem::reset(std::string_view name, Access access) {
    CVar* cvar = find(name);
    if (!cvar) return Status::failure("unknown cvar " + quoted(name));
    return assign(*cvar, cvar->defaultValue(), access);
}

std::vector<const CVar*> CVarSystem::list(std::string_view prefix) const {
    const std::string lowered = toLower(prefix);
    std::vector<const CVar*> out;
    for (auto it = cvars_.lower_bound(lowered); it != cvars_.end() && it->first.starts_with(lowered); ++it)
        out.push_back(&it->second);
    return out;
}

std::string CVarSystem::archive() const {
    std::string out;
    for (const auto& [key, cvar] : cvars_)
        if (hasFlag(cvar.flags(), CVarFlags::Archive)) out += "seta " + cvar.name() + " \"" + cvar.text() + "\"\n";
    return out;
}

Status CVarSystem::assign(CVar& cvar, CVarValue value, Access access) {
    if (access == Access::User && hasFlag(cvar.flags(), CVarFlags::ReadOnly))
        return Status::failure(quoted(cvar.name()) + " is read-only");
    if (value == cvar.value_) return Status::success();
    cvar.value_ = std::move(value);
    if (cvar.def_.onChange) cvar.def_.onChange(cvar);
    return Status::success();
}

}  // namespace af::console
