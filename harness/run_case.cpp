#include "harness/run_case.hpp"

#include <chrono>

#include "cases/catalogue.hpp"
#include "harness/claims.hpp"

namespace vivv {

CaseResult run_case(const CaseSpec& case_spec, std::optional<int> digits,
                    const std::function<void(const std::string&)>& progress) {
  auto started = std::chrono::steady_clock::now();
  CaseSpec spec = case_spec;
  if (digits) spec.digits = *digits;
  PrecisionGuard guard(spec.digits);
  using T = mpfr_real;
  std::vector<std::string> parameters;
  for (const auto& [name, value] : spec.parameters) parameters.push_back(value);
  CaseResult result;
  result.spec = spec;
  result.scalar = scalar_name<T>();
  result.digits = spec.digits;
  result.precision_bits = precision_bits<T>();
  visit_system<T>(spec.system, parameters, [&](auto system) {
    CaseContext context(spec, system, [&](const std::string& message) {
      if (progress) progress(spec.name + ": " + message);
    });
    result.reference_method = context.reference.method();
    result.reference_tolerance = to_decimal<T>(context.reference.tolerance());
    result.reference_cross_check = context.reference.cross_check();
    check_declared_orders(context);
    result.reference_check = check_reference(context.reference, context.initial, context.final_time);
    result.reference_error_estimate = result.reference_check.error_estimate;
    for (const auto& id : spec.claims) {
      if (progress) progress(spec.name + ": claim " + id);
      result.claims.push_back(evaluate_claim(id, context));
    }
    apply_reference_check(result.claims, result.reference_check);
    for (auto& claim : result.claims)
      if (auto it = spec.xfail.find(claim.id); it != spec.xfail.end()) apply_expected_failure(claim, it->second);
    T smallest = 0;
    for (const auto& claim : result.claims)
      for (const auto& series : claim.series)
        if (series.predicted_order)
          for (const auto& e : series.error) {
            T value = from_decimal<T>(e);
            if (value > 0 && (smallest == 0 || value < smallest)) smallest = value;
          }
    if (smallest > 0) {
      using std::log2;
      result.smallest_error = to_decimal<T>(smallest);
      result.guard_bits = static_cast<double>(result.precision_bits + log2(smallest));
    }
  });
  result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

}  // namespace vivv
