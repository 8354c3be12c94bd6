#pragma once
// Number spelling of the canonical writer (docs/formats.md §1.10).

#include "af/types.h"

#include <string>

namespace af {

// The float value of `v` as Doom's editor prints it: `%.10f` of the float widened to double,
// trailing zeros and a trailing `.` removed (0.2 -> "0.200000003", 10 -> "10", -0.0 -> "-0").
// Where ten decimals would not read back as the same float (magnitudes below about 1e-4), the
// shortest exponent form that does is used instead ("1e-12"), so a write never loses a value.
std::string formatDeclFloat(Real v);

}  // namespace af
