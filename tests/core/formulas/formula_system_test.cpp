// Formula systems: parsed once, recorded in T and sized at run time, as every case runs them. The
// catalogue's formula twins are its Lagrangians (values and symmetries against the C++ structs)
// and follow the closed forms where there are some, in double, quad and MPFR. Decimal literals are
// exact in the working precision.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "cases/case_file.hpp"
#include "cases/catalogue.hpp"
#include "cases/formula_parser.hpp"
#include "cases/systems.hpp"
#include "references/closed_forms.hpp"
#include "core/formulas/formula_system.hpp"
#include "core/structure/noether.hpp"
#include "core/autodiff/power_series.hpp"
#include "references/taylor_flow.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

VIVV_SCALAR_TEST_SUITE(FormulaSystemTest, Scalars);

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

// Runs f(catalogue system, its formula twin sized at run time, as every case runs it) for each of
// the eight, in T.
template <class T, class F>
void for_each_twin(F&& f) {
  std::apply([&](auto... compiled) { (f(compiled, make_formula_system<T, any_size>(twin_of(decltype(compiled)::name)),
                                        std::string(decltype(compiled)::name)), ...); },
             CatalogueSystems<T>{});
}

// States every catalogue system is regular at (|w| < 1 for the relativistic particle): the j-th.
template <class T>
State<T, any_size> probe_state(int n, int j) {
  State<T, any_size> x{zero_vector<T, any_size>(n), zero_vector<T, any_size>(n)};
  for (int i = 0; i < n; ++i) x.q[i] = T(3 + i + 2 * j) / 10, x.w[i] = T(2 - i - j) / 5;
  return x;
}

// The twin is the catalogue system's Lagrangian: the same value of L at five states (L written
// once in C++, cases/systems.hpp, and once as a formula, cases/case_file.cpp: two independent
// writings of one function), and the same symmetry. Its derivatives, DEL steps and flows are a
// formula system's, tested on their own (any_size_test.cpp; below against closed forms).
TYPED_TEST(FormulaSystemTest, CatalogueTwinsAreTheCatalogueLagrangians) {
  using T = TypeParam;
  using std::abs;
  for_each_twin<T>([&](const auto& compiled, const auto& formula, const std::string& name) {
    using Compiled = std::decay_t<decltype(compiled)>;
    constexpr int n = Compiled::dimension;
    ASSERT_EQ(formula.size(), n) << name;
    EXPECT_EQ(has_symmetry(formula), DeclaresSymmetry<Compiled>) << name;
    for (int j = 0; j < 5; ++j) {
      const State<T, any_size> x = probe_state<T>(n, j);
      Point<T, n> q, w;
      for (int i = 0; i < n; ++i) q[i] = x.q[i], w[i] = x.w[i];
      const T twin = formula.lagrangian(as_point<T, any_size>(x.q), as_point<T, any_size>(x.w));
      EXPECT_LE(abs(T(compiled.lagrangian(q, w) - twin)), this->working_tolerance()) << name << " at state " << j;
      if constexpr (DeclaresSymmetry<Compiled>) {
        const Point<T, n> xi = compiled.symmetry_generator(q);
        const Vector<T, any_size> twin_xi = symmetry_generator(formula, x.q);
        for (int i = 0; i < n; ++i) EXPECT_LE(abs(T(xi[i] - twin_xi[i])), this->working_tolerance()) << name;
      }
    }
  });
  // Negative control: a twin with one coefficient off (k = 1.001 in the pendulum) is told apart.
  const auto wrong = make_formula_system<T, any_size>(definition("w^2/2 - 1.001*(1 - cos(q))", {"q"}, {"w"}));
  const State<T, any_size> x = probe_state<T>(1, 0);
  const T wrong_value = wrong.lagrangian(as_point<T, any_size>(x.q), as_point<T, any_size>(x.w));
  EXPECT_GT(abs(T(Pendulum<T>{}.lagrangian(Point<T, 1>{x.q[0]}, Point<T, 1>{x.w[0]}) - wrong_value)),
            1000 * this->working_tolerance());
}

// The twins of the systems with a closed-form flow follow it: the Taylor flow of the twin to
// t = 1 against the closed form (references/closed_forms.hpp), which vivv's MPFR runs take as
// their reference; a twin with one coefficient off (k = 1.01 in the pendulum) is told apart.
TYPED_TEST(FormulaSystemTest, CatalogueTwinsFollowTheClosedForms) {
  using T = TypeParam;
  using std::abs;
  const T tolerance = testing::reference_tolerance<T>();
  const auto distance_to = [&](const FormulaSystemDefinition& twin, const State<T, any_size>& start,
                               const auto& closed) {
    const auto system = make_formula_system<T, any_size>(twin);
    const State<T, any_size> flowed = TaylorFlow<FormulaSystem<T, any_size>>(system, tolerance).advance(start, T(1));
    T worst = 0;
    for (int i = 0; i < start.q.size(); ++i)
      worst = std::max<T>({worst, T(abs(T(flowed.q[i] - closed.q[i]))), T(abs(T(flowed.w[i] - closed.w[i])))});
    return worst;
  };
  const State<T, any_size> x = probe_state<T>(1, 0);
  const State<T, 1> x1{Vector<T, 1>(x.q[0]), Vector<T, 1>(x.w[0])};
  EXPECT_LE(distance_to(twin_of("harmonic_oscillator"), x,
                        harmonic_oscillator_flow(HarmonicOscillator<T>{}, x1, T(1))),
            16 * tolerance);
  const State<T, 1> pendulum = pendulum_flow(Pendulum<T>{}, x1, T(1));
  EXPECT_LE(distance_to(twin_of("pendulum"), x, pendulum), 16 * tolerance);
  // k = 1.01: about 20 times the limit in double (3.7e-3 against 16 × 1e-5), far more elsewhere.
  EXPECT_GT(distance_to(definition("w^2/2 - 1.01*(1 - cos(q))", {"q"}, {"w"}), x, pendulum), 160 * tolerance);
  // Kepler from an orbit of eccentricity about 1/8.
  State<T, any_size> orbit = probe_state<T>(2, 0);
  orbit.w << T(-6) / 5, T(9) / 10;
  const State<T, 2> orbit2{Vector<T, 2>(orbit.q), Vector<T, 2>(orbit.w)};
  EXPECT_LE(distance_to(twin_of("kepler"), orbit, kepler_flow(Kepler<T>{}, orbit2, T(1))), 16 * tolerance);
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
    auto system = make_formula_system<T, any_size>(formula);
    const Vector<T, any_size> q = Vector<T, any_size>::Constant(1, x), w = Vector<T, any_size>::Zero(1);
    EXPECT_LE(abs(T(system.lagrangian(as_point<T, any_size>(q), as_point<T, any_size>(w)) - expected(x))),
              8 * this->working_tolerance())
        << text;
    EXPECT_LE(abs(T(check_formula_domain<T>(formula, {x}, {T(0)}) - expected(x))), 8 * this->working_tolerance())
        << text;
  }
}

// "0.1" is 1/10 rounded once in the working precision, never a double on the way.
TEST(FormulaSystemPrecision, DecimalLiteralsAreExactAt200Bits) {
  PrecisionGuard guard(60);
  ASSERT_GE(precision_bits<mpfr_real>(), 200);
  auto system = make_formula_system<mpfr_real, any_size>(definition("0.1 + q*w", {"q"}, {"w"}));
  const Vector<mpfr_real, any_size> zero = Vector<mpfr_real, any_size>::Zero(1);
  const mpfr_real value = system.lagrangian(as_point<mpfr_real, any_size>(zero), as_point<mpfr_real, any_size>(zero));
  EXPECT_EQ(value, mpfr_real(1) / 10);
  EXPECT_NE(value, mpfr_real(0.1));  // the double nearest 0.1 differs after bit 53
  EXPECT_GT(abs(value - mpfr_real(0.1)), mpfr_real("1e-18"));
}

// Meaningless formulas are errors at the offending character.
TEST(FormulaSystemErrors, NamePositionAndExpectation) {
  auto error_of = [](const std::string& text) {
    try {
      make_formula_system<double, any_size>(definition(text, {"q"}, {"w"}, {{"k", "1"}}));
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
