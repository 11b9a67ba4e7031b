// Symplecticity through random pairs: |ω(Jξ, Jη) − ω(ξ, η)| is |ξᵀ(JᵀΩJ − Ω)η|, rounding for a
// symplectic J and far above it for one entry off; a defect below t·‖D‖₂ is drawn at most a
// fraction t of the time (the bound the claim's miss probability rests on); the check of a
// Jacobian along random directions passes the map's own and fails one entry off by 10⁻³.
#include "core/structure/symplectic_probes.hpp"

#include <cmath>

#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

using V = Vector<double, any_size>;
using M = Matrix<double, any_size, any_size>;

template <class T>
Matrix<T, any_size, any_size> omega_matrix(int n) {
  Matrix<T, any_size, any_size> omega = Matrix<T, any_size, any_size>::Zero(2 * n, 2 * n);
  omega.topRightCorner(n, n).setIdentity();
  omega.bottomLeftCorner(n, n) = -Matrix<T, any_size, any_size>::Identity(n, n);
  return omega;
}

// A symplectic J on 2n coordinates: [[I, A], [0, I]]·[[I, 0], [S, I]] with A, S symmetric.
template <class T>
Matrix<T, any_size, any_size> symplectic_matrix(int n, GaussianProbes& draw) {
  using MT = Matrix<T, any_size, any_size>;
  MT a(n, n), s(n, n);
  for (int j = 0; j < n; ++j) {
    a.col(j) = draw.next<T>(n) / 4;
    s.col(j) = draw.next<T>(n) / 4;
  }
  a = MT(a + a.transpose()), s = MT(s + s.transpose());
  MT upper = MT::Identity(2 * n, 2 * n), lower = MT::Identity(2 * n, 2 * n);
  upper.topRightCorner(n, n) = a;
  lower.bottomLeftCorner(n, n) = s;
  return upper * lower;
}

VIVV_SCALAR_TEST_SUITE(SymplecticProbesTest, Scalars);

// The probe's value is ξᵀDη formed densely; a symplectic J gives rounding (measured in units of
// ε‖ξ‖‖η‖|J|², at most a few), one entry of J off by 10⁻⁶ gives at least 10⁻⁸ of ‖ξ‖‖η‖ in one
// of four pairs.
TYPED_TEST(SymplecticProbesTest, MeasuresTheDefectAndSeesOneEntryOff) {
  using T = TypeParam;
  using VT = Vector<T, any_size>;
  using MT = Matrix<T, any_size, any_size>;
  const int n = 20;
  GaussianProbes draw(7);
  const MT j = symplectic_matrix<T>(n, draw);
  const MT defect_matrix = MT(j.transpose() * omega_matrix<T>(n) * j - omega_matrix<T>(n));
  MT wrong = j;
  wrong(3, 25) += T(1e-6);
  T worst_rounding = 0, wrong_largest = 0;
  for (int pair = 0; pair < 4; ++pair) {
    const VT xi = draw.next<T>(2 * n), eta = draw.next<T>(2 * n);
    const ProbeDefect<T> probe = probe_defect<T>(xi, eta, VT(j * xi), VT(j * eta));
    using std::abs;
    EXPECT_LE(abs(T(probe.defect - abs(T(xi.dot(defect_matrix * eta))))),
              64 * epsilon<T>() * probe.norms * probe.stretch * probe.stretch);
    const T stretch = nan_max(T(1), probe.stretch);
    worst_rounding = nan_max(worst_rounding, T(probe.defect / (epsilon<T>() * probe.norms * stretch * stretch)));
    const ProbeDefect<T> off = probe_defect<T>(xi, eta, VT(wrong * xi), VT(wrong * eta));
    wrong_largest = nan_max(wrong_largest, T(off.defect / off.norms));
  }
  EXPECT_LE(worst_rounding, 4);
  EXPECT_GE(wrong_largest, T(1e-8));
}

// P(|ξᵀDη| < t‖D‖₂) ≤ t for antisymmetric D. The rank-2 D = σ(uvᵀ − vuᵀ) is the bound's
// worst case (ξᵀDη is σ times a Laplace variable: P = 1 − e^{−t}); a D of full rank is further
// from zero. 20000 pairs: the fraction below t = 0.1 within 4 standard deviations of the bound.
TEST(SymplecticProbes, DrawsADefectBelowAFractionOfItsNormAtMostThatOften) {
  const int n = 15;
  GaussianProbes draw(11);
  const V u = draw.next<double>(2 * n).normalized();
  V v = draw.next<double>(2 * n);
  v = (v - v.dot(u) * u).normalized();
  const M rank_two = 3 * (u * v.transpose() - v * u.transpose());  // ‖D‖₂ = 3
  M full = M::Zero(2 * n, 2 * n);
  for (int i = 0; i < n; ++i) full(i, n + i) = 3, full(n + i, i) = -3;  // ‖D‖₂ = 3, every direction
  const int pairs = 20000;
  int below_rank_two = 0, below_full = 0;
  for (int pair = 0; pair < pairs; ++pair) {
    const V xi = draw.next<double>(2 * n), eta = draw.next<double>(2 * n);
    below_rank_two += std::abs(xi.dot(rank_two * eta)) < 0.1 * 3;
    below_full += std::abs(xi.dot(full * eta)) < 0.1 * 3;
  }
  const double margin = 4 * std::sqrt(0.1 * 0.9 / pairs);
  EXPECT_LE(below_rank_two, (0.1 + margin) * pairs);
  EXPECT_NEAR(below_rank_two, (1 - std::exp(-0.1)) * pairs, margin * pairs);  // the Laplace law itself
  EXPECT_LE(below_full, below_rank_two);
}

// One seed, one sequence, in every scalar (the report's seed reproduces the run).
TYPED_TEST(SymplecticProbesTest, DrawsTheSameNumbersForOneSeed) {
  using T = TypeParam;
  GaussianProbes first(3), second(3);
  const Vector<T, any_size> a = first.next<T>(9), b = second.next<T>(9);
  const V as_double = GaussianProbes(3).next<double>(9);
  for (int i = 0; i < 9; ++i) {
    EXPECT_EQ(a[i], b[i]);
    EXPECT_EQ(static_cast<double>(a[i]), as_double[i]);
  }
}

// y ↦ (sin y₀ + y₁², y₀·y₂, exp(y₃/4), y₁ − y₂³): its Jacobian passes along two directions, and
// the same with ∂f₁/∂y₂ off by 10⁻³ fails.
TYPED_TEST(SymplecticProbesTest, ChecksAJacobianAlongDirections) {
  using T = TypeParam;
  using VT = Vector<T, any_size>;
  using MT = Matrix<T, any_size, any_size>;
  using std::sin, std::cos, std::exp;
  auto map = [](const VT& y) {
    VT out(4);
    out << sin(y[0]) + y[1] * y[1], y[0] * y[2], exp(y[3] / 4), y[1] - y[2] * y[2] * y[2];
    return out;
  };
  VT y(4);
  y << T(0.3), T(-1.2), T(0.7), T(2);
  MT j = MT::Zero(4, 4);
  j(0, 0) = cos(y[0]), j(0, 1) = 2 * y[1];
  j(1, 0) = y[2], j(1, 2) = y[0];
  j(2, 3) = exp(y[3] / 4) / 4;
  j(3, 1) = 1, j(3, 2) = -3 * y[2] * y[2];
  const VT scale = VT::Zero(4);
  GaussianProbes draw(5);
  const auto right = compare_directions_with_differences<T>(
      map, [&](const VT& v) { return VT(j * v); }, y, scale, draw, 2, epsilon<T>());
  EXPECT_TRUE(right.holds) << right.mismatch << " against " << right.allowed;
  MT off = j;
  off(1, 2) += T(1e-3);
  const auto wrong = compare_directions_with_differences<T>(
      map, [&](const VT& v) { return VT(off * v); }, y, scale, draw, 2, epsilon<T>());
  EXPECT_FALSE(wrong.holds) << wrong.mismatch << " against " << wrong.allowed;
}

}  // namespace
}  // namespace vivv
