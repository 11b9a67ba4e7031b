// A report against reports/schema.json (compiled in), with Valijson — the JSON Schema
// validator Debian packages as libvalijson-dev (BSD-2-Clause). `vivv report` checks every
// input and what it is about to write: a damaged or hand-edited report is refused naming the
// first place it breaks the schema, and nothing is written from it.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace vivv {

// Where `report` first breaks the schema and how ("cases[0].claims[1].verdict: Failed to match
// against any enum values"), or nothing when it follows it.
std::optional<std::string> schema_violation(const nlohmann::json& report);

}  // namespace vivv
