// af-check: parse .af files and report what is wrong with them, print them canonically, or
// dump them as JSON; or build a figure from its decl and skeleton and show its bodies,
// constraints and mass.
//
// Exit status: 0 when every file (or the figure) loads, 1 when anything has an error, 2 for bad
// usage. Warnings do not change the status, except with --strict, which makes every warning an
// error: a lint for files that should load in Doom 3 itself without a word.

#include "command_line_usage.h"
#include "af/text/af_parser.h"
#include "af/text/af_writer.h"
#include "af_json.h"
#include "figure_report.h"

#include <CLI/CLI.hpp>

#include <iostream>
#include <string>
#include <vector>

namespace {

struct Options {
    std::vector<std::string> files;
    bool format = false;
    bool json = false;
    std::string figure;
    std::string entity;
    std::vector<std::string> roots;
    bool strict = false;
};

// The diagnostics as this run reports them: with --strict every warning is an error.
std::vector<af::Diagnostic> asReported(std::vector<af::Diagnostic> diagnostics, bool strict) {
    if (strict)
        for (af::Diagnostic& d : diagnostics) d.severity = af::Severity::Error;
    return diagnostics;
}

bool anyError(const std::vector<af::Diagnostic>& diagnostics) {
    for (const af::Diagnostic& d : diagnostics)
        if (d.severity == af::Severity::Error) return true;
    return false;
}

std::string summary(const af::AFParseResult& r, const std::vector<af::Diagnostic>& diagnostics) {
    std::size_t errors = 0;
    for (const af::Diagnostic& d : diagnostics) errors += d.severity == af::Severity::Error;
    const std::size_t warnings = diagnostics.size() - errors;
    std::string out = r.file.path + ": " + (errors == 0 ? "ok" : "FAILED");
    for (const af::DeclAF& d : r.file.decls)
        out += ", " + d.name + " (" + std::to_string(d.bodies.size()) + " bodies, " +
               std::to_string(d.constraints.size()) + " constraints)";
    if (errors) out += ", " + std::to_string(errors) + " error(s)";
    if (warnings) out += ", " + std::to_string(warnings) + " warning(s)";
    return out;
}

nlohmann::ordered_json record(const af::AFParseResult& r, const std::vector<af::Diagnostic>& reported) {
    nlohmann::ordered_json decls = nlohmann::ordered_json::array();
    for (const af::DeclAF& d : r.file.decls) decls.push_back(af::toJson(d));
    nlohmann::ordered_json diagnostics = nlohmann::ordered_json::array();
    for (const af::Diagnostic& d : reported) diagnostics.push_back(af::toJson(d));
    return {{"file", r.file.path}, {"ok", !anyError(reported)}, {"decls", decls}, {"diagnostics", diagnostics}};
}

int checkFiles(const Options& options) {
    bool allOk = true;
    for (const std::string& path : options.files) {
        const af::AFParseResult result = af::loadAFFile(path);
        const std::vector<af::Diagnostic> reported = asReported(result.diagnostics.all(), options.strict);
        const bool ok = !anyError(reported);
        allOk = allOk && ok;
        if (options.json) {
            std::cout << record(result, reported).dump() << '\n';
            continue;
        }
        for (const af::Diagnostic& d : reported) std::cerr << d.format() << '\n';
        if (options.format) {
            if (ok) std::cout << af::writeAFFile(result.file);
        } else {
            std::cout << summary(result, reported) << '\n';
        }
    }
    return allOk ? 0 : 1;
}

// A figure by decl name (its model from `settings { model }`) or an AF entity by entityDef name.
int checkFigure(const Options& options) {
    std::vector<std::filesystem::path> roots(options.roots.begin(), options.roots.end());
    if (roots.empty()) roots.emplace_back(AF_DATA_DIR);
    const af::ResourceIndex index(roots);
    const af::AFResources resources =
        options.entity.empty() ? index.resolveFigure(options.figure) : index.resolveAFEntity(options.entity);

    // What the figure's own .af file said when it was read, then what finding and building it said.
    std::vector<af::Diagnostic> diagnostics;
    if (resources.figure)
        for (const af::Diagnostic& d : index.diagnostics())
            if (d.file == resources.figure->file) diagnostics.push_back(d);
    diagnostics.insert(diagnostics.end(), resources.diagnostics.begin(), resources.diagnostics.end());
    std::optional<af::FigureResult> built;
    if (resources.ok()) {
        built = af::buildFigure(resources);
        diagnostics.insert(diagnostics.end(), built->diagnostics.begin(), built->diagnostics.end());
    }
    diagnostics = asReported(std::move(diagnostics), options.strict);
    const af::Figure* figure = built && built->ok() && !anyError(diagnostics) ? &*built->figure : nullptr;
    if (options.json) {
        std::cout << af::figureReportJson(figure, resources, diagnostics).dump() << '\n';
    } else {
        for (const af::Diagnostic& d : diagnostics) std::cerr << d.format() << '\n';
        if (figure) std::cout << af::figureReportText(*figure, resources);
    }
    return figure ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
    Options options;
    CLI::App app{"Checks Doom 3-style articulated figure (.af) files: every problem is reported as "
                 "file:line:col. Exit status 0 when all files load, 1 when any has an error (or, with --strict, a "
                 "warning), 2 for bad usage."};
    app.add_option("files", options.files, ".af files to check");
    auto* format = app.add_flag("--format", options.format,
                                "print each file in the canonical layout of the Doom 3 AF editor");
    app.add_flag("--json", options.json, "print JSON: one record per file and line, or one for the figure")
        ->excludes(format);
    auto* figure = app.add_option("--figure", options.figure,
                                  "build the named figure on its model's af_pose skeleton and show it");
    auto* entity = app.add_option("--entity", options.entity, "the same for an AF entityDef")->excludes(figure);
    app.add_option("--root", options.roots,
                   "a mod folder laid out like Doom's base/ (af/, def/, models/); repeat for more, "
                   "later ones override earlier ones (default: the af data folder of this build)");
    app.add_flag("--strict", options.strict,
                 "treat every warning as an error (exit status 1): for files that should load in Doom 3 "
                 "without a word");
    format->excludes(figure)->excludes(entity);
    const auto exitStatus = af::tools::parseCommandLine(app, argc, argv, "af-check", [&] {
        const bool figureMode = !options.figure.empty() || !options.entity.empty();
        if (figureMode == !options.files.empty())
            throw CLI::ValidationError("give .af files, or --figure/--entity NAME, but not both");
    });
    if (exitStatus) return *exitStatus;
    return options.files.empty() ? checkFigure(options) : checkFiles(options);
}
