#pragma once
// JSON views of parsed data for the tools' --json output: every field, so two files with the
// same meaning give the same JSON. Numbers are the shortest decimals of their float values.

#include "af/text/decl_af.h"
#include "af/text/diagnostics.h"

#include <nlohmann/json.hpp>

namespace af {

nlohmann::ordered_json toJson(const AFVector& v);
nlohmann::ordered_json toJson(const DeclAF& decl);
nlohmann::ordered_json toJson(const Diagnostic& d);

}  // namespace af
