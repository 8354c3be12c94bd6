#pragma once
// What `af-check --figure` and `--entity` print: a built figure with its bodies, constraints,
// trees and mass, as text for people and as JSON for scripts.

#include "af/figure/figure.h"
#include "af/text/resource_index.h"

#include <nlohmann/json.hpp>

#include <string>

namespace af {

std::string figureReportText(const Figure& figure, const AFResources& resources);

// `figure` may be null when it could not be built; the diagnostics say why.
nlohmann::ordered_json figureReportJson(const Figure* figure, const AFResources& resources,
                                        const std::vector<Diagnostic>& diagnostics);

}  // namespace af
