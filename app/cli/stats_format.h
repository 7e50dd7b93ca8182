#pragma once
// Text and JSON renderings of BuildStats for `accelviz-cli stats`.
#include <string>

#include "structure.h"

namespace cli {

/// Human-readable, one "key: value" per line.
std::string stats_text(const std::string& scene, const std::string& structure, const std::string& params,
                       const accel::Scene& s, const accel::BuildStats& b);
/// One JSON object with the same fields.
std::string stats_json(const std::string& scene, const std::string& structure, const std::string& params,
                       const accel::Scene& s, const accel::BuildStats& b);
/// JSON string literal with escapes.
std::string json_quote(const std::string& s);

}  // namespace cli
