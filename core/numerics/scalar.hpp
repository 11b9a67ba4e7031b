// Scalar types, their Eigen traits, the MPFR precision guard and decimal I/O.
//
// vivv computes in double, long double, quad (boost::multiprecision::float128)
// and MPFR at a precision chosen at run time. Everything in core/ and
// references/ is templated on one of these; this file is the one place where
// their traits live.
#pragma once

#include <array>
#include <initializer_list>

#include <Eigen/Dense>
#include <boost/multiprecision/eigen.hpp>
#include <boost/multiprecision/float128.hpp>
#include <boost/multiprecision/mpfr.hpp>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace vivv {

using quad = boost::multiprecision::float128;
// MPFR at the run-time default precision, without expression templates (so
// that Eigen and our automatic differentiation see plain values).
using mpfr_real = boost::multiprecision::number<boost::multiprecision::mpfr_float_backend<0>,
                                                boost::multiprecision::et_off>;

template <class T>
inline constexpr bool is_mpfr_v = std::is_same_v<T, mpfr_real>;

// Sets the MPFR working precision (decimal digits) for the scope and restores
// the previous one on exit. Boost 1.74 keeps one process-wide default, so
// computations at different precisions run in different processes.
class PrecisionGuard {
 public:
  explicit PrecisionGuard(unsigned digits10) : previous_(mpfr_real::default_precision()) {
    if (digits10 < 10) throw std::invalid_argument("MPFR precision below 10 decimal digits");
    mpfr_real::default_precision(digits10);
  }
  ~PrecisionGuard() { mpfr_real::default_precision(previous_); }
  PrecisionGuard(const PrecisionGuard&) = delete;
  PrecisionGuard& operator=(const PrecisionGuard&) = delete;

 private:
  unsigned previous_;
};

// Bits of the significand of T at the current precision.
template <class T>
int precision_bits() {
  if constexpr (is_mpfr_v<T>) {
    return static_cast<int>(mpfr_get_prec(mpfr_real(0).backend().data()));
  } else {
    return std::numeric_limits<T>::digits;
  }
}

// Unit roundoff scale: 2^(1 − bits), the machine epsilon of T now.
template <class T>
T epsilon() {
  using std::ldexp;
  return ldexp(T(1), 1 - precision_bits<T>());
}

// Name of the scalar type as written in reports.
template <class T>
std::string scalar_name() {
  if constexpr (std::is_same_v<T, double>) return "double";
  if constexpr (std::is_same_v<T, long double>) return "long double";
  if constexpr (std::is_same_v<T, quad>) return "float128";
  if constexpr (is_mpfr_v<T>) return "mpfr";
}

// The error for a decimal beyond T's range, naming the text, the scalar and its range.
template <class T>
std::out_of_range out_of_range_for(const std::string& text) {
  std::ostringstream range;
  range << std::setprecision(2) << std::numeric_limits<T>::denorm_min() << " and "
        << std::numeric_limits<T>::max();
  return std::out_of_range("'" + text.substr(0, 100) + (text.size() > 100 ? "…" : "") +
                           "' is out of range for " + scalar_name<T>() +
                           ": its magnitude must lie between " + range.str() + ", or be 0");
}

// Parses a decimal string exactly as T rounds it; never through a double.
template <class T>
T from_decimal(const std::string& text) {
  if (text.empty()) throw std::invalid_argument("empty number");
  if constexpr (std::is_same_v<T, double> || std::is_same_v<T, long double>) {
    // strtod, not std::stod: stod throws a bare "stod" for a subnormal result such as 1e-320,
    // which is a valid double.
    errno = 0;
    char* end = nullptr;
    const T value = std::is_same_v<T, double> ? std::strtod(text.c_str(), &end)
                                              : std::strtold(text.c_str(), &end);
    if (end != text.c_str() + text.size() || std::isspace(static_cast<unsigned char>(text.front())))
      throw std::invalid_argument("not a number: '" + text.substr(0, 100) + "'");
    if (errno == ERANGE && (std::isinf(value) || value == 0)) {
      throw out_of_range_for<T>(text);
    }
    return value;
  } else {
    // Boost accepts only a complete decimal number and throws otherwise.
    T value;
    try {
      value = T(text);
    } catch (const std::exception&) {
      throw std::invalid_argument("not a number: '" + text.substr(0, 100) + "'");
    }
    // float128 and MPFR round a number beyond their range to infinity or zero without a word:
    // "1e5000" in float128 would enter a computation as inf, "1e-5000" as 0.
    using std::isinf;
    const std::size_t mantissa_end = text.find_first_of("eE");
    const bool nonzero =
        text.substr(0, mantissa_end).find_first_of("123456789") != std::string::npos;
    if (isinf(value) || (value == 0 && nonzero)) {
      throw out_of_range_for<T>(text);
    }
    return value;
  }
}

// Decimal digits that round-trip T at the current precision.
template <class T>
int round_trip_digits() {
  return static_cast<int>(std::ceil(precision_bits<T>() * 0.30102999566398120)) + 1;
}

// Writes x in scientific notation with every digit needed to read it back.
template <class T>
std::string to_decimal(const T& x) {
  std::ostringstream out;
  out.precision(round_trip_digits<T>());
  out << std::scientific << x;
  return out.str();
}

// Writes x in scientific notation with `digits` significant digits (for messages).
template <class T>
std::string to_decimal(const T& x, int digits) {
  std::ostringstream out;
  out.precision(digits - 1);
  out << std::scientific << x;
  return out.str();
}

// Writes x with three significant digits in the stream's shortest form ("1e-12", "0.00123"): a
// tolerance in a reference's description.
template <class T>
std::string three_digits(const T& x) {
  std::ostringstream out;
  out << std::setprecision(3) << x;
  return out.str();
}

template <class T, int n>
using Vector = Eigen::Matrix<T, n, 1>;
template <class T, int rows, int cols>
using Matrix = Eigen::Matrix<T, rows, cols>;

// The dimension of a system known only at run time (a formula system of any size): as a
// template argument it makes every vector and matrix Eigen-dynamic and every jet a heap jet
// (core/autodiff/jet.hpp). The tool runs every system at it; fixed dimensions remain for what a
// C++ user registers, the benchmarks and the unit tests.
inline constexpr int any_size = Eigen::Dynamic;

// n numbers of type S: std::array for a fixed n, std::vector for any_size (the arguments of L, a
// Point, and the small vectors of core/autodiff/small_linear_algebra.hpp).
template <class S, int n>
struct CoordinatesType {
  using type = std::array<S, n>;
};
template <class S>
struct CoordinatesType<S, any_size> {
  using type = std::vector<S>;
};
template <class S, int n>
using Coordinates = typename CoordinatesType<S, n>::type;

// 2n, n + k at compile time: any_size stays any_size.
constexpr int twice(int n) { return n == any_size ? any_size : 2 * n; }
constexpr int plus(int n, int k) { return n == any_size ? any_size : n + k; }

// A zero vector of n components and an n × m zero matrix, for fixed and run-time sizes alike
// (a fixed size asserts that n is it).
template <class T, int N>
Vector<T, N> zero_vector(int n) {
  return Vector<T, N>::Zero(n);
}
template <class T, int R, int C>
Matrix<T, R, C> zero_matrix(int rows, int cols) {
  return Matrix<T, R, C>::Zero(rows, cols);
}

// A vector as "(x_1, x_2, …)" with `digits` significant digits each, for messages.
template <class T, int n>
std::string to_decimal_tuple(const Vector<T, n>& v, int digits = 8) {
  std::string text = "(";
  for (int i = 0; i < v.size(); ++i) text += (i ? ", " : "") + to_decimal<T>(v[i], digits);
  return text + ")";
}

// max(a, b), NaN when either is NaN: std::max(a, NaN) returns a, so that a NaN in a measurement
// would vanish into a reduction (and a claim pass on the rest).
template <class T>
T nan_max(const T& a, const T& b) {
  using std::isnan;
  if (isnan(a)) return a;
  if (isnan(b)) return b;
  return a < b ? b : a;
}

// min(a, b), NaN when either is NaN.
template <class T>
T nan_min(const T& a, const T& b) {
  using std::isnan;
  if (isnan(a)) return a;
  if (isnan(b)) return b;
  return b < a ? b : a;
}

// The largest of `values`, NaN when any is NaN.
template <class T>
T nan_max(std::initializer_list<T> values) {
  T largest = *values.begin();
  for (const T& value : values) largest = nan_max(largest, value);
  return largest;
}

// Max norm of a vector; NaN if a component is NaN (std::max would drop it and report 0).
template <class T, int n>
T max_norm(const Vector<T, n>& v) {
  using std::abs, std::isnan;
  T result = 0;
  for (int i = 0; i < v.size(); ++i) {
    if (isnan(v[i])) return v[i];
    result = std::max<T>(result, abs(v[i]));
  }
  return result;
}

}  // namespace vivv

// Boost 1.74's Eigen traits for multiprecision numbers lack digits(),
// min_exponent(), max_exponent(), infinity() and quiet_NaN(), which Eigen 3.4
// uses; these full specializations supply them for the two types we use.
namespace Eigen {
template <class Number>
struct VivvMultiprecisionTraits {
  using Real = Number;
  using NonInteger = Number;
  using Literal = Number;
  using Nested = Number;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 1,
    ReadCost = 1,
    AddCost = 4,
    MulCost = 8
  };
  static int digits() { return vivv::precision_bits<Number>(); }
  static int digits10() { return static_cast<int>(digits() * 0.30102999566398120); }
  static int max_digits10() { return vivv::round_trip_digits<Number>(); }
  static int min_exponent() { return std::numeric_limits<Number>::min_exponent; }
  static int max_exponent() { return std::numeric_limits<Number>::max_exponent; }
  static Number infinity() { return std::numeric_limits<Number>::infinity(); }
  static Number quiet_NaN() { return std::numeric_limits<Number>::quiet_NaN(); }
  static Number epsilon() { return vivv::epsilon<Number>(); }
  static Number dummy_precision() { return 1000 * epsilon(); }
  static Number highest() { return (std::numeric_limits<Number>::max)(); }
  static Number lowest() { return std::numeric_limits<Number>::lowest(); }
};
template <>
struct NumTraits<vivv::mpfr_real> : VivvMultiprecisionTraits<vivv::mpfr_real> {};
template <>
struct NumTraits<vivv::quad> : VivvMultiprecisionTraits<vivv::quad> {};
}  // namespace Eigen
