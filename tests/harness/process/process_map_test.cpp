// A one-step map in another program (harness/process/process_map.hpp) at 1, 2, 7 and 64
// coordinates sized at run time, in double, long double, float128 and MPFR: the program
// (chain_verlet.py, Störmer–Verlet for the chain of tests/chain_formula.hpp in mpmath at the
// digits it is greeted with) is stepped through the protocol, and
//   - its step is the same Verlet step computed here in the scalar, to a few ulps, and five steps
//     in one request (extension "steps") are five of them;
//   - the Jacobian symplecticity measures, by central differences of a second instance at
//     2D + 10 digits, is the central differences of that step here (to their truncation) and
//     symplectic to its rounding unit;
//   - the negative: the same program with h·1.001 in its drift differs from the step by about
//     10⁻³ h |p|, far beyond the tolerance the correct one meets.
#include "harness/process/process_map.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/formulas/formula_system.hpp"
#include "core/structure/symplectic.hpp"
#include "core/structure/symplectic_probes.hpp"
#include "tests/chain_formula.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

VIVV_SCALAR_TEST_SUITE(ProcessMapAnySize, AllScalars);

using testing::distance;

// The chain's Verlet step, here in T: p½ = p + h/2 ∂L/∂q(q), q' = q + h p½, p' = p½ + h/2 ∂L/∂q(q')
// (p = w for this L).
template <class System>
State<typename System::Scalar, any_size> verlet(const System& system, const State<typename System::Scalar, any_size>& x,
                                                const typename System::Scalar& h) {
  using T = typename System::Scalar;
  const int n = static_cast<int>(x.q.size());
  const Vector<T, any_size> zero = zero_vector<T, any_size>(n);
  const Vector<T, any_size> half = x.w + h / 2 * lagrangian_derivatives(system, x.q, zero).dL_dq;
  State<T, any_size> next{x.q + h * half, half};
  next.w = half + h / 2 * lagrangian_derivatives(system, next.q, zero).dL_dq;
  return next;
}

template <class T>
std::unique_ptr<ProcessMap<FormulaSystem<T, any_size>>> chain_program(const FormulaSystem<T, any_size>& system,
                                                                     int n, std::vector<std::string> options = {}) {
  const FormulaSystemDefinition definition = testing::chain(n);
  nlohmann::json system_json = {{"name", definition.name},
                                {"lagrangian", definition.text},
                                {"coordinates", definition.coordinates},
                                {"velocities", definition.velocities}};
  std::vector<std::string> command{"/usr/bin/python3", std::string(VIVV_SOURCE_DIR) + "/tests/harness/process/chain_verlet.py"};
  command.insert(command.end(), options.begin(), options.end());
  MapProcess::Options process{command, std::string(VIVV_SOURCE_DIR) + "/tests/harness/process", 60};
  return std::make_unique<ProcessMap<FormulaSystem<T, any_size>>>(system, process, system_json, 2, T(1));
}

template <class T>
void expect_program_step_and_jacobian(int n) {
  const auto system = make_formula_system<T, any_size>(testing::chain(n));
  const State<T, any_size> x = testing::chain_state<T, any_size>(n);
  const T h = T(1) / 16;
  const auto program = chain_program<T>(system, n);
  const State<T, any_size> expected = verlet(system, x, h);
  const State<T, any_size> stepped = program->step(x, h);
  const T tolerance = 64 * epsilon<T>();
  EXPECT_LE(distance(stepped.q, expected.q), tolerance);
  EXPECT_LE(distance(stepped.w, expected.w), tolerance);

  // Five steps in one request (the extension "steps", which vivv_map takes up): the five steps here.
  State<T, any_size> five = x;
  for (int k = 0; k < 5; ++k) five = verlet(system, five, h);
  const std::optional<State<T, any_size>> batched = program->steps(x, h, 5);
  ASSERT_TRUE(batched.has_value());
  EXPECT_LE(distance(batched->q, five.q), 5 * tolerance);
  EXPECT_LE(distance(batched->w, five.w), 5 * tolerance);

  // The Jacobian against central differences of the step here, at width ε^(1/3): truncation and
  // rounding both about ε^(2/3) times the map's third derivative and size (the chain's are O(1)).
  const Matrix<T, any_size, any_size> J = program->jacobian(x, h);
  ASSERT_EQ(J.rows(), 2 * n);
  using std::cbrt;
  const T width = cbrt(epsilon<T>());
  Matrix<T, any_size, any_size> differences(2 * n, 2 * n);
  for (int j = 0; j < 2 * n; ++j) {
    State<T, any_size> plus = x, minus = x;
    (j < n ? plus.q[j] : plus.w[j - n]) += width;
    (j < n ? minus.q[j] : minus.w[j - n]) -= width;
    const State<T, any_size> a = verlet(system, plus, h), b = verlet(system, minus, h);
    for (int i = 0; i < n; ++i)
      differences(i, j) = (a.q[i] - b.q[i]) / (2 * width), differences(n + i, j) = (a.w[i] - b.w[i]) / (2 * width);
  }
  EXPECT_LE(distance(J, differences), 16 * width * width);
  const T defect = symplecticity_defect(J);
  EXPECT_LE(defect, 1024 * program->last_jacobian_unit()) << "|J^T Omega J - Omega| = " << defect;

  // J applied to vectors by differences along them (symplecticity's probes above 16 coordinates):
  // J·v, at the second instance's digits as the columns are, so to far below ε of |J||v|.
  GaussianProbes draw(7);
  const std::vector<Vector<T, any_size>> directions{draw.next<T>(2 * n), draw.next<T>(2 * n)};
  const std::vector<Vector<T, any_size>> products = program->jacobian_along(x, h, directions);
  ASSERT_EQ(products.size(), 2u);
  const T size = std::max(T(1), T(J.cwiseAbs().maxCoeff()));
  for (std::size_t k = 0; k < 2; ++k)
    EXPECT_LE(distance(products[k], Vector<T, any_size>(J * directions[k])),
              64 * epsilon<T>() * size * directions[k].cwiseAbs().sum());

  // The negative: h·1.001 in the drift moves q' by 10⁻³ h |p½|, far beyond the tolerance, and its
  // products along the same vectors are not the right map's: ∂q'/∂p moves by 10⁻³ h.
  const auto wrong = chain_program<T>(system, n, {"--h-factor", "1.001"});
  const State<T, any_size> off = wrong->step(x, h);
  EXPECT_GT(distance(off.q, expected.q), T(1) / 100000);
  const std::vector<Vector<T, any_size>> wrong_products = wrong->jacobian_along(x, h, directions);
  EXPECT_GT(distance(wrong_products[0], products[0]), T(1) / 1000000);
}

TYPED_TEST(ProcessMapAnySize, StepsAndDifferentiatesAProgramAtOneTwoSevenAndSixtyFourCoordinates) {
  for (int n : {1, 2, 7, 64}) {
    SCOPED_TRACE(std::to_string(n) + " coordinates");
    expect_program_step_and_jacobian<TypeParam>(n);
  }
}

}  // namespace
}  // namespace vivv
