// The symplecticity defect and the balancing of a Jacobian, at n = 1, 2, 7 and 64 in double,
// long double, float128 and MPFR:
//   - the defect is the largest entry of JᵀΩJ − Ω written from J's n × n blocks, to a few ulps of
//     |J|², on matrices that are not symplectic;
//   - a product of shears with dyadic entries is symplectic exactly, and stays so (defect 0) once
//     balanced by powers of two, however far apart the exponents;
//   - balancing moves a defect by exactly the powers of two the change of coordinates predicts,
//     so it cannot hide one: (J̃ᵀΩJ̃ − Ω) = S⁻ᵀ (JᵀΩJ − Ω) S⁻¹.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/structure/symplectic.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

VIVV_SCALAR_TEST_SUITE(SymplecticBlocksTest, AllScalars);

const std::vector<int> sizes = {1, 2, 7, 64};

template <class T>
using Square = Matrix<T, any_size, any_size>;

template <class T>
Square<T> omega(int n) {
  Square<T> o = Square<T>::Zero(2 * n, 2 * n);
  o.topRightCorner(n, n).setIdentity();
  o.bottomLeftCorner(n, n) = -Square<T>::Identity(n, n);
  return o;
}

// A symmetric n × n matrix with entries k/8, k in [−8, 8]: exact in every scalar, and its
// products with others of its kind stay exact for the sizes here.
template <class T>
Square<T> symmetric(std::mt19937& random, int n) {
  std::uniform_int_distribution<int> k(-8, 8);
  Square<T> s(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j <= i; ++j) s(i, j) = s(j, i) = T(k(random)) / 8;
  return s;
}

// [[I, S1], [0, I]]·[[I, 0], [S2, I]]: symplectic for symmetric S1, S2, and computed exactly.
template <class T>
Square<T> shears(std::mt19937& random, int n) {
  Square<T> upper = Square<T>::Identity(2 * n, 2 * n), lower = Square<T>::Identity(2 * n, 2 * n);
  upper.topRightCorner(n, n) = symmetric<T>(random, n);
  lower.bottomLeftCorner(n, n) = symmetric<T>(random, n);
  return upper * lower;
}

TYPED_TEST(SymplecticBlocksTest, DefectIsTheLargestEntryOfTheBlocksIdentity) {
  // JᵀΩJ − Ω = [[AᵀC − CᵀA, AᵀD − CᵀB − I], [BᵀC − DᵀA + I, BᵀD − DᵀB]] for J = [[A, B], [C, D]].
  using T = TypeParam;
  using std::abs;
  std::mt19937 random(7);
  for (int n : sizes) {
    Square<T> j(2 * n, 2 * n);
    for (int r = 0; r < 2 * n; ++r)
      for (int c = 0; c < 2 * n; ++c) j(r, c) = this->uniform(random, -1, 1);
    const Square<T> a = j.topLeftCorner(n, n), b = j.topRightCorner(n, n), c = j.bottomLeftCorner(n, n),
                    d = j.bottomRightCorner(n, n), identity = Square<T>::Identity(n, n);
    const T expected = std::max({max_entry<T, any_size, any_size>(Square<T>(a.transpose() * c - c.transpose() * a)),
                                 max_entry<T, any_size, any_size>(Square<T>(b.transpose() * d - d.transpose() * b)),
                                 max_entry<T, any_size, any_size>(Square<T>(a.transpose() * d - c.transpose() * b - identity)),
                                 max_entry<T, any_size, any_size>(Square<T>(b.transpose() * c - d.transpose() * a + identity))});
    const T measured = symplecticity_defect<T, any_size>(j);
    // Each entry is a sum of 2n products of entries at most 1, computed as one sum (dense) or as
    // two of n terms (blocks): each within γ_2n·2n ≈ 4n² ulps of the exact value.
    EXPECT_LE(abs(T(measured - expected)), T(8 * n * n) * epsilon<T>()) << "n = " << n;
    EXPECT_GT(measured, T(0)) << "n = " << n;
  }
}

TYPED_TEST(SymplecticBlocksTest, ShearsAreSymplecticExactlyAndStaySoBalanced) {
  using T = TypeParam;
  std::mt19937 random(11);
  for (int n : sizes) {
    const Square<T> j = shears<T>(random, n);
    EXPECT_EQ((symplecticity_defect<T, any_size>(j)), T(0)) << "n = " << n;
    std::vector<int> exponents(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) exponents[static_cast<std::size_t>(i)] = (i % 5 - 2) * 7;  // −14 … 14
    EXPECT_EQ((symplecticity_defect<T, any_size>(balanced<T, any_size>(j, exponents))), T(0)) << "n = " << n;
    // No exponents: the Jacobian as it is.
    EXPECT_EQ((balanced<T, any_size>(j, {})), j);
  }
}

TYPED_TEST(SymplecticBlocksTest, BalancingMovesADefectByItsPowersOfTwo) {
  using T = TypeParam;
  using std::ldexp;
  std::mt19937 random(13);
  for (int n : sizes) {
    Square<T> j = shears<T>(random, n);
    // A defect in the last coordinate's (q, p) pair: p_n' gains 2^−10 q_n.
    j(2 * n - 1, n - 1) += ldexp(T(1), -10);
    std::vector<int> exponents(static_cast<std::size_t>(n), 0);
    exponents.back() = -13;  // a light body: q̃ = 2^−13 q, p̃ = 2^13 p
    const Square<T> defect = j.transpose() * omega<T>(n) * j - omega<T>(n);
    const Square<T> b = balanced<T, any_size>(j, exponents);
    const Square<T> balanced_defect = b.transpose() * omega<T>(n) * b - omega<T>(n);
    // S = diag(2^e, 2^−e): (J̃ᵀΩJ̃ − Ω)_rc = 2^(−g_r − g_c) (JᵀΩJ − Ω)_rc, g = (e, −e).
    auto g = [&](int i) { return i < n ? exponents[static_cast<std::size_t>(i)] : -exponents[static_cast<std::size_t>(i - n)]; };
    for (int r = 0; r < 2 * n; ++r)
      for (int c = 0; c < 2 * n; ++c)
        ASSERT_EQ(T(balanced_defect(r, c)), T(ldexp(T(defect(r, c)), -g(r) - g(c)))) << "n = " << n << " at " << r << ", " << c;
    EXPECT_GT((symplecticity_defect<T, any_size>(b)), T(0)) << "n = " << n;
    EXPECT_EQ((symplecticity_defect<T, any_size>(b)), (max_entry<T, any_size, any_size>(balanced_defect))) << "n = " << n;
  }
}

// A NaN anywhere in the Jacobian is a NaN defect, in the block form too.
TYPED_TEST(SymplecticBlocksTest, NotANumberIsNeverAPass) {
  using T = TypeParam;
  std::mt19937 random(17);
  for (int n : sizes) {
    Square<T> j = shears<T>(random, n);
    j(n, 2 * n - 1) = std::numeric_limits<T>::quiet_NaN();
    using std::isnan;
    EXPECT_TRUE(isnan((symplecticity_defect<T, any_size>(j)))) << "n = " << n;
  }
}

}  // namespace
}  // namespace vivv
