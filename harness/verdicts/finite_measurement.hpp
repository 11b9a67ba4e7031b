// A measurement that left the finite numbers (docs/claims.md, "No NaN passes"): a NaN or an
// infinity cannot be compared with a tolerance — `NaN <= tol` is false and `inf <= inf` true — and
// std::max drops a NaN (core/numerics/scalar.hpp, nan_max). Where a claim meets one it throws
// NonFiniteMeasurement naming where it came from; Claim::evaluate (harness/claims/claim.hpp) makes
// that claim `error` with the message, and the case's other claims are judged.
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/numerics/scalar.hpp"

namespace vivv {

struct NonFiniteMeasurement : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Throws NonFiniteMeasurement("<what> is <value>: …") unless `value` is a finite number.
template <class T>
void require_finite(const T& value, const std::string& what) {
  using std::isfinite;
  if (isfinite(value)) return;
  throw NonFiniteMeasurement(what + " is " + to_decimal<T>(value, 6) +
                             ": a measurement that is not a finite number cannot be judged "
                             "against any tolerance (an overflow, or 0/0, in the map's answer or "
                             "in what vivv computed from it)");
}

}  // namespace vivv
