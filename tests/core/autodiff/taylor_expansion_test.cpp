// The MPFR inner product of the Taylor recurrences (core/autodiff/taylor_expansion.hpp):
// fixed_point_dot sums the exact products in one fixed-point accumulator and
// rounds once. Its error bound, |r − Σ a_j b_j| ≤ ½ ulp(r) + K·2^(E − 64(n+1))
// (K terms, E the largest exponent of a product, n limbs), is checked against
// the exact sum (products at twice the precision, mpfr_sum) on random inputs
// with zeros, mixed signs, spread exponents and deliberate cancellation, at
// precisions on both sides of the 2048-bit fixed-point limit.
#include "core/autodiff/taylor_expansion.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace vivv {
namespace {

// |r − Σ a_j b_j| in units of the bound ½ ulp(r) + K·2^(E − 64(n+1)); at most 1 when the bound holds.
double error_over_bound(const std::vector<mpfr_real>& a, const std::vector<mpfr_real>& b,
                        const mpfr_real& r) {
  const mpfr_prec_t precision = mpfr_get_prec(r.backend().data());
  const long limbs = (precision + 63) / 64;
  const int count = static_cast<int>(a.size());
  std::vector<mpfr_t> products(count);
  std::vector<mpfr_ptr> pointers(count);
  mpfr_exp_t top = mpfr_get_emin();
  for (int j = 0; j < count; ++j) {
    mpfr_init2(products[j], 2 * precision);
    mpfr_mul(products[j], a[j].backend().data(), b[count - 1 - j].backend().data(), MPFR_RNDN);  // exact
    if (!mpfr_zero_p(products[j])) top = std::max(top, mpfr_get_exp(products[j]));
    pointers[j] = products[j];
  }
  mpfr_t exact, difference, bound, term;
  mpfr_inits2(4 * precision + 256, exact, difference, bound, term, static_cast<mpfr_ptr>(nullptr));
  mpfr_sum(exact, pointers.data(), count, MPFR_RNDN);  // exact at this precision
  mpfr_sub(difference, r.backend().data(), exact, MPFR_RNDN);
  mpfr_abs(difference, difference, MPFR_RNDN);
  mpfr_set_ui_2exp(bound, count, top - 64 * (limbs + 1), MPFR_RNDN);
  if (!mpfr_zero_p(r.backend().data())) {
    mpfr_set_ui_2exp(term, 1, mpfr_get_exp(r.backend().data()) - precision - 1, MPFR_RNDN);  // ½ ulp
    mpfr_add(bound, bound, term, MPFR_RNDN);
  }
  double ratio = mpfr_zero_p(difference) ? 0.0 : mpfr_get_d(difference, MPFR_RNDN) / mpfr_get_d(bound, MPFR_RNDN);
  mpfr_clears(exact, difference, bound, term, static_cast<mpfr_ptr>(nullptr));
  for (auto& product : products) mpfr_clear(product);
  return ratio;
}

class FixedPointDotTest : public ::testing::TestWithParam<int> {};

TEST_P(FixedPointDotTest, WithinItsBoundOnRandomAndCancellingSums) {
  PrecisionGuard guard(GetParam());
  std::mt19937 random(GetParam());
  std::uniform_int_distribution<int> exponent(-40, 40), mantissa(-1000000, 1000000), zero(0, 7);
  constexpr int count = 40;
  double worst = 0;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<mpfr_real> a(count), b(count);
    for (int j = 0; j < count; ++j) {
      a[j] = zero(random) == 0 ? mpfr_real(0) : ldexp(mpfr_real(mantissa(random)) / 3, exponent(random));
      b[j] = ldexp(mpfr_real(mantissa(random)) / 7, exponent(random));
    }
    if (trial % 2 == 1)  // cancellation: the second half repeats the first with the sign flipped
      for (int j = count / 2; j < count; ++j) {
        a[j] = -a[j - count / 2];
        b[count - 1 - j] = b[count - 1 - (j - count / 2)] * (1 + ldexp(mpfr_real(1), -30));
      }
    mpfr_real r, scratch;
    taylor_detail::set_dot(r, a.data(), b.data(), 0, count - 1, count - 1, scratch);
    worst = std::max(worst, error_over_bound(a, b, r));
  }
  EXPECT_LE(worst, 1.0);
}

// 20 and 77 digits (2 and 5 limbs), 300 digits (16 limbs), 700 digits (over the 2048-bit limit:
// the term-by-term path, whose error is also within this bound for these sums).
INSTANTIATE_TEST_SUITE_P(Digits, FixedPointDotTest, ::testing::Values(20, 77, 300, 700));

}  // namespace
}  // namespace vivv
