// af-check: parse .af files and report what is wrong with them, print them canonically, or
// dump them as JSON.
//
// Exit status: 0 when every file loads, 1 when any file has an error, 2 for bad usage.

#include "af/text/af_parser.h"
#include "af/text/af_writer.h"
#include "af_json.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

namespace {

struct Options {
    std::vector<std::string> files;
    bool format = false;
    bool json = false;
};

std::string summary(const af::AFParseResult& r) {
    std::string out = r.file.path + ": " + (r.ok() ? "ok" : "FAILED");
    for (const af::DeclAF& d : r.file.decls)
        out += ", " + d.name + " (" + std::to_string(d.bodies.size()) + " bodies, " +
               std::to_string(d.constraints.size()) + " constraints)";
    if (r.diagnostics.errorCount()) out += ", " + std::to_string(r.diagnostics.errorCount()) + " error(s)";
    if (r.diagnostics.warningCount()) out += ", " + std::to_string(r.diagnostics.warningCount()) + " warning(s)";
    return out;
}

nlohmann::ordered_json record(const af::AFParseResult& r) {
    nlohmann::ordered_json decls = nlohmann::ordered_json::array();
    for (const af::DeclAF& d : r.file.decls) decls.push_back(af::toJson(d));
    nlohmann::ordered_json diagnostics = nlohmann::ordered_json::array();
    for (const af::Diagnostic& d : r.diagnostics.all()) diagnostics.push_back(af::toJson(d));
    return {{"file", r.file.path}, {"ok", r.ok()}, {"decls", decls}, {"diagnostics", diagnostics}};
}

}  // namespace

int main(int argc, char** argv) {
    Options options;
    CLI::App app{"Checks Doom 3-style articulated figure (.af) files: every problem is reported as "
                 "file:line:col. Exit status 0 when all files load, 1 when any has an error, 2 for bad usage."};
    app.add_option("files", options.files, ".af files to check")->required();
    auto* format = app.add_flag("--format", options.format,
                                "print each file in the canonical layout of the Doom 3 AF editor");
    app.add_flag("--json", options.json, "print one JSON record per file and line (the full parsed data)")
        ->excludes(format);
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        app.exit(e);
        return 2;
    }

    bool allOk = true;
    for (const std::string& path : options.files) {
        const af::AFParseResult result = af::loadAFFile(path);
        allOk = allOk && result.ok();
        if (options.json) {
            std::cout << record(result).dump() << '\n';
            continue;
        }
        std::cerr << result.diagnostics.formatAll();
        if (options.format) {
            if (result.ok()) std::cout << af::writeAFFile(result.file);
        } else {
            std::cout << summary(result) << '\n';
        }
    }
    return allOk ? 0 : 1;
}
