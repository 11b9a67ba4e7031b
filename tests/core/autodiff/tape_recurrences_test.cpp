// The Taylor recurrences of every operation the tape knows, each against a
// closed form, in double, quad and MPFR, through both Taylor engines
// (TaylorExpansion, used by the reference flow, and the generic
// solution_taylor_coefficients, used by taylor and exact psi).
//
// The probe is a 2-D system whose first component moves linearly, x1 = a + b t
// (x1'' = 0), and whose second is driven by one operation of x1:
// x2'' = op(x1). Then x2's Taylor coefficient k + 2 is c_k / ((k + 1)(k + 2)),
// c_k the k-th Taylor coefficient of op(a + b t), known in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "core/lagrangian/taylor_curve.hpp"
#include "core/autodiff/taylor_expansion.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

VIVV_SCALAR_TEST_SUITE(TapeRecurrenceTest, Scalars);

// One operation: how to record it on x1 and the k-th Taylor coefficient of op(a + b t).
template <class T>
struct OperationProbe {
  std::string name;
  std::function<TapeScalar<T>(const TapeScalar<T>&)> record;
  std::function<T(const T& a, const T& b, int k)> coefficient;
};

// k!
using testing::factorial;

// binom(c, k) for real c.
template <class T>
T binomial(const T& c, int k) {
  T value = 1;
  for (int j = 0; j < k; ++j) value = value * (c - j) / (j + 1);
  return value;
}

template <class T>
std::vector<OperationProbe<T>> probes() {
  using std::cos, std::exp, std::log, std::pow, std::sin, std::sqrt;
  const T third = T(1) / 3;
  const T half_pi = boost::math::constants::half_pi<T>();
  return {
      {"exp", [](const TapeScalar<T>& x) { return exp(x); },
       [](const T& a, const T& b, int k) { return T(exp(a) * pow(b, k) / factorial<T>(k)); }},
      {"log", [](const TapeScalar<T>& x) { return log(x); },
       [](const T& a, const T& b, int k) {
         if (k == 0) return T(log(a));
         return T((k % 2 == 1 ? 1 : -1) * pow(b / a, k) / k);
       }},
      {"sqrt", [](const TapeScalar<T>& x) { return sqrt(x); },
       [](const T& a, const T& b, int k) { return T(sqrt(a) * binomial(T(1) / 2, k) * pow(b / a, k)); }},
      {"pow 1/3", [third](const TapeScalar<T>& x) { return pow(x, third); },
       [third](const T& a, const T& b, int k) { return T(pow(a, third) * binomial(third, k) * pow(b / a, k)); }},
      {"division 1/x", [](const TapeScalar<T>& x) { return 1 / x; },
       [](const T& a, const T& b, int k) { return T(pow(-b / a, k) / a); }},
      {"division (x + 2)/(3x)", [](const TapeScalar<T>& x) { return (x + 2) / (3 * x); },
       [](const T& a, const T& b, int k) {  // 1/3 + (2/3)/x
         return T((k == 0 ? T(1) / 3 : T(0)) + T(2) / 3 * pow(-b / a, k) / a);
       }},
      {"sin", [](const TapeScalar<T>& x) { return sin(x); },
       [half_pi](const T& a, const T& b, int k) { return T(sin(a + k * half_pi) * pow(b, k) / factorial<T>(k)); }},
      {"cos", [](const TapeScalar<T>& x) { return cos(x); },
       [half_pi](const T& a, const T& b, int k) { return T(cos(a + k * half_pi) * pow(b, k) / factorial<T>(k)); }},
      // atan(a + bt): c_k = (−1)^{k−1} b^k sin(kφ) / (k ρ^k), ρ = √(1 + a²), φ = atan(1/a) (a > 0).
      {"atan", [](const TapeScalar<T>& x) { return atan(x); },
       [](const T& a, const T& b, int k) {
         using std::atan;
         if (k == 0) return T(atan(a));
         const T rho = sqrt(1 + a * a), phi = atan(1 / a);
         return T((k % 2 == 1 ? 1 : -1) * pow(b / rho, k) * sin(k * phi) / k);
       }},
      {"square", [](const TapeScalar<T>& x) { return x * x; },
       [](const T& a, const T& b, int k) { return k == 0 ? T(a * a) : k == 1 ? T(2 * a * b) : k == 2 ? T(b * b) : T(0); }},
  };
}

TYPED_TEST(TapeRecurrenceTest, EveryOperationMatchesItsClosedForm) {
  using T = TypeParam;
  using std::abs, std::max;
  constexpr int order = 12;
  const T a = T(13) / 10, b = T(-2) / 5;  // x1 = a + b t stays in every domain near t = 0
  const T x2 = T(1) / 7, v2 = T(3) / 4;
  for (const auto& probe : probes<T>()) {
    TapeRecording<T> recording(4);  // (x1, x2, v1, v2)
    TapeScalar<T> x1 = recording.input(0);
    TapeScalar<T> zero = x1 - x1;
    Tape<T> tape = recording.finish({zero, probe.record(x1)});
    std::vector<T> x0{a, x2}, v0{b, v2};
    auto generic = solution_taylor_coefficients<T, T>(tape, x0, v0, order);
    TaylorExpansion<T> expansion(tape);
    expansion.expand(x0.data(), v0.data(), order);
    for (int k = 0; k + 2 <= order; ++k) {
      const T expected = probe.coefficient(a, b, k) / ((k + 1) * (k + 2));
      const T tolerance = 64 * this->working_tolerance() * max(T(1), abs(expected));
      EXPECT_LE(abs(T(generic[1][k + 2] - expected)), tolerance) << probe.name << ", coefficient " << k + 2;
      EXPECT_LE(abs(T(expansion.position(1, k + 2) - expected)), tolerance)
          << probe.name << " (TaylorExpansion), coefficient " << k + 2;
    }
    // x1 is linear: its recurrence must not invent curvature.
    for (int k = 2; k <= order; ++k) EXPECT_EQ(generic[0][k], T(0)) << probe.name;
  }
}

// Negative control: the closed form of a neighbouring operation (log for exp) is rejected,
// so the comparison above can fail.
TYPED_TEST(TapeRecurrenceTest, AWrongClosedFormIsRejected) {
  using T = TypeParam;
  using std::abs;
  auto all = probes<T>();
  TapeRecording<T> recording(4);
  TapeScalar<T> x1 = recording.input(0);
  Tape<T> tape = recording.finish({x1 - x1, all[0].record(x1)});  // exp
  const T a = T(13) / 10, b = T(-2) / 5;
  auto generic = solution_taylor_coefficients<T, T>(tape, {a, T(0)}, {b, T(0)}, 6);
  int mismatches = 0;
  for (int k = 0; k + 2 <= 6; ++k)
    mismatches += abs(T(generic[1][k + 2] - all[1].coefficient(a, b, k) / ((k + 1) * (k + 2)))) >
                  this->working_tolerance();
  EXPECT_EQ(mismatches, 5);
}

}  // namespace
}  // namespace vivv
