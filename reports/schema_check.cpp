#include "reports/schema_check.hpp"

#include <memory>
#include <string>
#include <vector>

#include <valijson/adapters/nlohmann_json_adapter.hpp>
#include <valijson/schema.hpp>
#include <valijson/schema_parser.hpp>
#include <valijson/validator.hpp>

namespace vivv {

extern const char* const report_schema_text;

namespace {

// The schema, parsed once. reports/schema.json declares draft 2020-12 but uses only keywords
// draft 7 has ($ref into $defs, allOf/anyOf, enum/const, pattern, bounds): Valijson's draft-7
// parser reads it as written.
const valijson::Schema& report_schema_document() {
  static const std::unique_ptr<const valijson::Schema> schema = [] {
    const nlohmann::json document = nlohmann::json::parse(report_schema_text);
    auto parsed = std::make_unique<valijson::Schema>();
    valijson::SchemaParser parser(valijson::SchemaParser::kDraft7);
    const valijson::adapters::NlohmannJsonAdapter adapter(document);
    parser.populateSchema(adapter, *parsed);
    return parsed;
  }();
  return *schema;
}

// "<root>[cases][0][claims]" -> "cases[0].claims".
std::string readable_path(const std::vector<std::string>& context) {
  std::string path;
  for (const std::string& part : context) {
    if (part == "<root>") continue;
    const bool index = part.size() > 2 && part.front() == '[' &&
                       part.find_first_not_of("0123456789", 1) == part.size() - 1;
    if (index) {
      path += part;
    } else {
      const std::string name = part.size() >= 2 && part.front() == '[' ? part.substr(1, part.size() - 2) : part;
      path += (path.empty() ? "" : ".") + name;
    }
  }
  return path.empty() ? "the report" : path;
}

}  // namespace

std::optional<std::string> schema_violation(const nlohmann::json& report) {
  valijson::Validator validator;
  valijson::ValidationResults results;
  const valijson::adapters::NlohmannJsonAdapter adapter(report);
  if (validator.validate(report_schema_document(), adapter, &results)) return std::nullopt;
  // Valijson lists the innermost failure first, then each enclosing one: the first is the place.
  valijson::ValidationResults::Error error;
  if (!results.popError(error)) return std::string("the report: does not follow the schema");
  return readable_path(error.context) + ": " + error.description;
}

}  // namespace vivv
