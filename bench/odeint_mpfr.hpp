// Boost 1.74's odeint looks for the scalar of a state by following value_type,
// and number::value_type is number itself, so it never stops for a
// multiprecision scalar. This full specialization stops it at vivv::mpfr_real.
#pragma once

#include <boost/numeric/odeint.hpp>

#include "core/numerics/scalar.hpp"

namespace boost::numeric::odeint::detail {
template <>
struct extract_value_type<vivv::mpfr_real, void> {
  using type = vivv::mpfr_real;
};
}  // namespace boost::numeric::odeint::detail
