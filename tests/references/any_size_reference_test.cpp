// The reference flow and odeint's maps on systems sized at run time (issue 50 item 7), in double,
// long double, float128 and MPFR: a chain of n coordinates written as a formula (fixed ends, a
// quartic on-site term), n = 1, 2, 7 and 64.
//   every n:   the reference keeps its promises — F_{−t}(F_t(x)) = x and E(F_t(x)) = E(x) to a small
//              multiple of its tolerance, its own error estimate within it — and odeint's
//              velocity Verlet has the Jacobian central differences of its step give. (At 1 and 2
//              coordinates the flow is also checked against closed forms: the catalogue's twins in
//              tests/core/formulas/formula_system_test.cpp.)
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "cases/formula_parser.hpp"
#include "core/formulas/formula_system.hpp"
#include "core/maps/odeint_map.hpp"
#include "references/taylor_reference.hpp"
#include "tests/chain_formula.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

VIVV_SCALAR_TEST_SUITE(AnySizeReferenceTest, AllScalars);

using testing::chain;
using testing::chain_state;
using testing::distance;

// What the tests ask of the reference: ε^(2/3) (about 4e-11 in double, 1e-40 at MPFR's 60 digits),
// raised to its own floor where that is larger.
template <class T>
T requested_tolerance() {
  using std::cbrt;
  return cbrt(epsilon<T>()) * cbrt(epsilon<T>());
}

template <class T>
void expect_reference_keeps_its_promises(int n) {
  using std::abs;
  const auto system = make_formula_system<T, any_size>(chain(n));
  TaylorReference<FormulaSystem<T, any_size>> reference(system, requested_tolerance<T>());
  const State<T, any_size> x = chain_state<T, any_size>(n);
  const T t = T(1) / 2;
  const State<T, any_size> there = reference.advance(x, t);
  ASSERT_EQ(there.q.size(), n);
  const State<T, any_size> back = reference.advance(there, -t);
  // Two advances, each within its tolerance relative to the state's size (about 1 here).
  const T allowed = 4 * reference.tolerance();
  EXPECT_LE(distance(back.q, x.q), allowed) << "n = " << n;
  EXPECT_LE(distance(back.w, x.w), allowed) << "n = " << n;
  const T e0 = energy(system, x.q, x.w), e1 = energy(system, there.q, there.w);
  EXPECT_LE(abs(T(e1 - e0)), T(4 * n) * reference.tolerance()) << "n = " << n;
  EXPECT_LE(reference.estimate_error(x, t), reference.tolerance()) << "n = " << n;
  // The flow moved the state (a flow that returned x itself would pass the rest).
  EXPECT_GT(distance(there.q, x.q), T(1) / 100);
}

template <class T>
void expect_odeint_jacobian_from_differences(int n) {
  using std::cbrt;
  const auto system = make_formula_system<T, any_size>(chain(n));
  const State<T, any_size> x = chain_state<T, any_size>(n);
  const auto map = make_odeint_map<T, any_size>("velocity_verlet", separable_form(system, x));
  const T h = T(1) / 8;
  const auto jacobian = map->jacobian(x, h);
  ASSERT_EQ(jacobian.rows(), 2 * n);
  // Central differences of the step on (q, p) (unit masses: p = w), a few columns of a long chain.
  const T width = cbrt(epsilon<T>());
  for (int j : n <= 8 ? std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13}
                      : std::vector<int>{0, n / 2, n - 1, n, n + n / 2, 2 * n - 1}) {
    if (j >= 2 * n) continue;
    State<T, any_size> up = x, down = x;
    (j < n ? up.q[j] : up.w[j - n]) += width;
    (j < n ? down.q[j] : down.w[j - n]) -= width;
    const State<T, any_size> a = map->step(up, h), b = map->step(down, h);
    Vector<T, any_size> column(2 * n);
    for (int i = 0; i < n; ++i)
      column[i] = (a.q[i] - b.q[i]) / (2 * width), column[n + i] = (a.w[i] - b.w[i]) / (2 * width);
    EXPECT_LE(distance(Vector<T, any_size>(jacobian.col(j)), column), 100 * width * width)
        << "n = " << n << ", column " << j;
  }
}

TYPED_TEST(AnySizeReferenceTest, ReferenceAndOdeintAtOneTwoSevenAndSixtyFourCoordinates) {
  for (int n : {1, 2, 7, 64}) {
    expect_reference_keeps_its_promises<TypeParam>(n);
    expect_odeint_jacobian_from_differences<TypeParam>(n);
  }
}

}  // namespace
}  // namespace vivv
