// Formula systems: parsed once, recorded in T, and then the same Lagrangian
// system as their compiled twins in the catalogue — values, derivatives, DEL
// trajectories and Taylor reference flows agree to working precision, in
// double, quad and MPFR. Decimal literals are exact in the working precision.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "cases/case_file.hpp"
#include "cases/catalogue.hpp"
#include "cases/formula_parser.hpp"
#include "cases/systems.hpp"
#include "core/qxq/del_evolution.hpp"
#include "core/formulas/formula_system.hpp"
#include "core/structure/noether.hpp"
#include "core/autodiff/power_series.hpp"
#include "references/taylor_flow.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

template <class T>
class FormulaSystemTest : public testing::ScalarTest<T> {};
TYPED_TEST_SUITE(FormulaSystemTest, testing::Scalars, testing::ScalarNames);

FormulaSystemDefinition definition(const std::string& text, std::vector<std::string> coordinates,
                                   std::vector<std::string> velocities,
                                   std::vector<std::pair<std::string, std::string>> parameters = {}) {
  return {"formula",
          text,
          parse_formula(text),
          std::move(coordinates),
          std::move(velocities),
          std::move(parameters),
          {},
          nullptr};
}

// The catalogue's systems as the formulas a case in double, long double or float128 runs
// them through (cases/case_file.cpp), with their default parameters.
FormulaSystemDefinition twin_of(const std::string& name) {
  for (const auto& info : system_catalogue())
    if (info.name == name) {
      std::vector<std::pair<std::string, std::string>> parameters;
      for (const auto& p : info.parameters) parameters.emplace_back(p.name, p.default_value);
      return catalogue_twin(name, parameters);
    }
  throw std::invalid_argument("no system " + name);
}

// Runs f(catalogue system, its formula twin) for each of the eight, in T.
template <class T, class F>
void for_each_twin(F&& f) {
  f(PaperExample<T>{}, make_formula_system<T, 1>(twin_of("paper_example")), "paper_example");
  f(HarmonicOscillator<T>{}, make_formula_system<T, 1>(twin_of("harmonic_oscillator")), "harmonic_oscillator");
  f(Pendulum<T>{}, make_formula_system<T, 1>(twin_of("pendulum")), "pendulum");
  f(RelativisticParticle<T>{}, make_formula_system<T, 1>(twin_of("relativistic_particle")), "relativistic_particle");
  f(ChargedParticle<T>{}, make_formula_system<T, 2>(twin_of("charged_particle")), "charged_particle");
  f(Kepler<T>{}, make_formula_system<T, 2>(twin_of("kepler")), "kepler");
  f(HenonHeiles<T>{}, make_formula_system<T, 2>(twin_of("henon_heiles")), "henon_heiles");
  f(DoublePendulum<T>{}, make_formula_system<T, 2>(twin_of("double_pendulum")), "double_pendulum");
}

// A state every catalogue system is regular at (|w| < 1 for the relativistic particle).
template <class T, int n>
std::pair<Vector<T, n>, Vector<T, n>> probe_state() {
  Vector<T, n> q, w;
  for (int i = 0; i < n; ++i) q[i] = T(3 + i) / 10, w[i] = T(2 - i) / 5;
  return {q, w};
}

TYPED_TEST(FormulaSystemTest, CatalogueTwinsHaveTheSameDerivatives) {
  using T = TypeParam;
  using std::abs;
  for_each_twin<T>([&](const auto& compiled, const auto& formula, const std::string& name) {
    constexpr int n = std::decay_t<decltype(compiled)>::dimension;
    auto [q, w] = probe_state<T, n>();
    auto a = lagrangian_derivatives(compiled, q, w);
    auto b = lagrangian_derivatives(formula, q, w);
    const T tolerance = this->working_tolerance();
    EXPECT_LE(abs(T(a.value - b.value)), tolerance) << name;
    EXPECT_LE(T((a.dL_dq - b.dL_dq).cwiseAbs().maxCoeff()), tolerance) << name;
    EXPECT_LE(T((a.dL_dw - b.dL_dw).cwiseAbs().maxCoeff()), tolerance) << name;
    EXPECT_LE((a.d2L_dw2 - b.d2L_dw2).cwiseAbs().maxCoeff(), tolerance) << name;
    EXPECT_LE((a.d2L_dwdq - b.d2L_dwdq).cwiseAbs().maxCoeff(), tolerance) << name;
    // The twin declares the same symmetry, or none.
    using Compiled = std::decay_t<decltype(compiled)>;
    EXPECT_EQ(has_symmetry(formula), DeclaresSymmetry<Compiled>) << name;
    if constexpr (DeclaresSymmetry<Compiled>) {
      EXPECT_LE(T((symmetry_generator(compiled, q) - symmetry_generator(formula, q)).cwiseAbs().maxCoeff()), tolerance)
          << name;
    }
  });
}

TYPED_TEST(FormulaSystemTest, CatalogueTwinsHaveTheSameTrajectories) {
  using T = TypeParam;
  for_each_twin<T>([&](const auto& compiled, const auto& formula, const std::string& name) {
    constexpr int n = std::decay_t<decltype(compiled)>::dimension;
    auto [q0, w0] = probe_state<T, n>();
    // From the probe state Kepler's orbit has eccentricity 0.98 and passes within 0.005 of the
    // centre, too close for h = 1/20: start it on an orbit of eccentricity about 1/8.
    if constexpr (n == 2)
      if (name == "kepler") w0 << T(-6) / 5, T(9) / 10;
    const T h = T(1) / 20;
    constexpr int steps = 40;
    // DEL (midpoint) from the same start: every q_k to working precision.
    QxQDiscretization<T> midpoint;
    auto scheme = matched_scheme(midpoint);
    Vector<T, n> q1_compiled = start_from_momentum(compiled, midpoint, q0, w0, h);
    Vector<T, n> q1_formula = start_from_momentum(formula, midpoint, q0, w0, h);
    auto a = del_trajectory(compiled, scheme, q0, q1_compiled, h, steps);
    auto b = del_trajectory(formula, scheme, q0, q1_formula, h, steps);
    T worst = 0;
    for (int k = 0; k <= steps; ++k) worst = std::max<T>(worst, T((a.q[k] - b.q[k]).cwiseAbs().maxCoeff()));
    EXPECT_LE(worst, steps * this->working_tolerance()) << name << " (DEL)";
    // Taylor reference flow to t = 1.
    const T tolerance = testing::reference_tolerance<T>();
    using Compiled = std::decay_t<decltype(compiled)>;
    using Formula = std::decay_t<decltype(formula)>;
    State<T, n> start{q0, w0};
    auto exact_a = TaylorFlow<Compiled>(compiled, tolerance).advance(start, T(1));
    auto exact_b = TaylorFlow<Formula>(formula, tolerance).advance(start, T(1));
    EXPECT_LE(T((exact_a.q - exact_b.q).cwiseAbs().maxCoeff()), 16 * tolerance) << name << " (Taylor flow)";
    EXPECT_LE(T((exact_a.w - exact_b.w).cwiseAbs().maxCoeff()), 16 * tolerance) << name << " (Taylor flow)";
  });
}

// Negative control: a twin with one coefficient off (k = 1.001 in the pendulum) is told apart.
TYPED_TEST(FormulaSystemTest, AWrongTwinIsToldApart) {
  using T = TypeParam;
  auto wrong = make_formula_system<T, 1>(definition("w^2/2 - 1.001*(1 - cos(q))", {"q"}, {"w"}));
  auto [q0, w0] = probe_state<T, 1>();
  const T h = T(1) / 20;
  QxQDiscretization<T> midpoint;
  Pendulum<T> pendulum;
  auto a = del_trajectory(pendulum, matched_scheme(midpoint), q0, Vector<T, 1>(q0 + h * w0), h, 40);
  auto b = del_trajectory(wrong, matched_scheme(midpoint), q0, Vector<T, 1>(q0 + h * w0), h, 40);
  EXPECT_GT(T((a.q.back() - b.q.back()).cwiseAbs().maxCoeff()), 1000 * 40 * this->working_tolerance());
}

// Every function of the grammar, in T and through the tape, against the scalar's own.
TYPED_TEST(FormulaSystemTest, FunctionsMatchTheScalarsOwn) {
  using T = TypeParam;
  using std::abs, std::atan, std::cos, std::cosh, std::exp, std::log, std::sin, std::sinh, std::sqrt, std::tan,
      std::tanh, std::pow;
  const T x = T(7) / 10;
  const std::vector<std::pair<std::string, std::function<T(const T&)>>> cases = {
      {"sqrt(q)", [](const T& v) { return T(sqrt(v)); }},  {"exp(q)", [](const T& v) { return T(exp(v)); }},
      {"log(q)", [](const T& v) { return T(log(v)); }},    {"sin(q)", [](const T& v) { return T(sin(v)); }},
      {"cos(q)", [](const T& v) { return T(cos(v)); }},    {"tan(q)", [](const T& v) { return T(tan(v)); }},
      {"sinh(q)", [](const T& v) { return T(sinh(v)); }},  {"cosh(q)", [](const T& v) { return T(cosh(v)); }},
      {"tanh(q)", [](const T& v) { return T(tanh(v)); }},  {"atan(q)", [](const T& v) { return T(atan(v)); }},
      {"q^(1/3)", [](const T& v) { return T(pow(v, T(1) / 3)); }},
      {"q^-3", [](const T& v) { return T(1 / (v * v * v)); }},
      {"2^3^2", [](const T&) { return T(512); }},
      {"-q^2", [](const T& v) { return T(-(v * v)); }},
      {"pi*q", [](const T& v) { return T(boost::math::constants::pi<T>() * v); }},
  };
  for (const auto& [text, expected] : cases) {
    auto formula = definition(text + " + w^2", {"q"}, {"w"});
    auto system = make_formula_system<T, 1>(formula);
    Point<T, 1> q{x}, w{T(0)};
    EXPECT_LE(abs(T(system.lagrangian(q, w) - expected(x))), 8 * this->working_tolerance()) << text;
    EXPECT_LE(abs(T(check_formula_domain<T>(formula, {x}, {T(0)}) - expected(x))), 8 * this->working_tolerance())
        << text;
  }
}

// "0.1" is 1/10 rounded once in the working precision, never a double on the way.
TEST(FormulaSystemPrecision, DecimalLiteralsAreExactAt200Bits) {
  PrecisionGuard guard(60);
  ASSERT_GE(precision_bits<mpfr_real>(), 200);
  auto system = make_formula_system<mpfr_real, 1>(definition("0.1 + q*w", {"q"}, {"w"}));
  Point<mpfr_real, 1> zero{mpfr_real(0)};
  const mpfr_real value = system.lagrangian(zero, zero);
  EXPECT_EQ(value, mpfr_real(1) / 10);
  EXPECT_NE(value, mpfr_real(0.1));  // the double nearest 0.1 differs after bit 53
  EXPECT_GT(abs(value - mpfr_real(0.1)), mpfr_real("1e-18"));
}

// Meaningless formulas are errors at the offending character.
TEST(FormulaSystemErrors, NamePositionAndExpectation) {
  auto error_of = [](const std::string& text) {
    try {
      make_formula_system<double, 1>(definition(text, {"q"}, {"w"}, {{"k", "1"}}));
    } catch (const FormulaError& error) {
      return std::to_string(error.position) + ": " + error.what();
    }
    return std::string("no error");
  };
  EXPECT_EQ(error_of("w^2/2 - kk*q").substr(0, 10), "8: unknown");
  EXPECT_NE(error_of("w^2/2 - kk*q").find("expected one of: k, q, w, pi"), std::string::npos);
  EXPECT_EQ(error_of("w^q").substr(0, 3), "2: ");
  EXPECT_NE(error_of("w^q").find("constant exponent"), std::string::npos);
  EXPECT_NE(error_of("foo(q)").find("unknown function 'foo'"), std::string::npos);
  EXPECT_NE(error_of("L(q, w)").find("discrete Lagrangian"), std::string::npos);
  EXPECT_NE(error_of("sin(q, w)").find("one argument"), std::string::npos);
  // An unknown name with two arguments is unknown, not a function of the wrong arity.
  EXPECT_NE(error_of("r2(q, w)").find("unknown function 'r2'"), std::string::npos);
  EXPECT_NE(error_of("q[1]").find("not a vector"), std::string::npos);
  EXPECT_EQ(error_of("w^2 + k"), "no error");
  try {
    parse_formula("(w^2 + q");
    FAIL() << "no error";
  } catch (const FormulaError& error) {
    EXPECT_EQ(error.position, 8);
    EXPECT_STREQ(error.what(), "expected ')'");
  }
}

// Outside the domain at a state: named, with the argument's value.
TEST(FormulaSystemErrors, DomainAtTheInitialState) {
  auto formula = definition("w^2/2 + sqrt(q) + log(1 + q)", {"q"}, {"w"});
  EXPECT_NO_THROW(check_formula_domain<double>(formula, {0.5}, {0.0}));
  try {
    check_formula_domain<double>(formula, {-0.5}, {0.0});
    FAIL() << "no error";
  } catch (const FormulaError& error) {
    EXPECT_EQ(error.position, 8);
    EXPECT_NE(std::string(error.what()).find("sqrt of -0.5"), std::string::npos) << error.what();
  }
  EXPECT_THROW(check_formula_domain<double>(definition("log(q) + w^2", {"q"}, {"w"}), {0.0}, {0.0}), FormulaError);
  EXPECT_THROW(check_formula_domain<double>(definition("1/q + w^2", {"q"}, {"w"}), {0.0}, {0.0}), FormulaError);
  EXPECT_THROW(check_formula_domain<double>(definition("q^0.5 + w^2", {"q"}, {"w"}), {-1.0}, {0.0}), FormulaError);
}

}  // namespace
}  // namespace vivv

namespace vivv {
namespace {

// atan and log of a power series (used when a formula L is expanded along a solution) against
// their closed forms on a + b h: atan_k = (−1)^{k−1} b^k sin(kφ) / (k ρ^k), log_k = (−1)^{k−1} (b/a)^k / k.
TYPED_TEST(FormulaSystemTest, PowerSeriesAtanAndLogMatchTheirClosedForms) {
  using T = TypeParam;
  using std::abs, std::atan, std::log, std::pow, std::sin, std::sqrt;
  const T a = T(13) / 10, b = T(-2) / 5;
  const auto line = PowerSeries<T>::from({a, b, T(0), T(0), T(0), T(0), T(0), T(0)});
  const PowerSeries<T> arc = atan(line), logarithm = log(line);
  const T rho = sqrt(1 + a * a), phi = atan(1 / a);
  EXPECT_LE(abs(T(arc[0] - atan(a))), this->working_tolerance());
  EXPECT_LE(abs(T(logarithm[0] - log(a))), this->working_tolerance());
  for (int k = 1; k < line.length(); ++k) {
    const T sign = k % 2 == 1 ? 1 : -1;
    EXPECT_LE(abs(T(arc[k] - sign * pow(b / rho, k) * sin(k * phi) / k)), this->working_tolerance()) << k;
    EXPECT_LE(abs(T(logarithm[k] - sign * pow(b / a, k) / k)), this->working_tolerance()) << k;
  }
  // Negative control: the closed form of atan is not log's.
  EXPECT_GT(abs(T(arc[2] - (-1) * pow(b / a, 2) / 2)), T(1) / 100);
}

}  // namespace
}  // namespace vivv
