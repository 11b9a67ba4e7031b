// Lagrangians and discrete Lagrangians given as C++ code by a program that links vivv
// (harness/library/vivv.hpp: register_system, register_discrete_lagrangian) instead of as formulas in a
// case file. The code is written once for any scalar; vivv records it on a tape in the case's
// scalar (core/autodiff/tape.hpp), exactly as it records a formula, so everything downstream — jets,
// Taylor series, every claim — runs it like a formula system or an "expression" L_d. A tape is
// a straight-line program: branches on values are taken once, where the recording runs.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/numerics/scalar.hpp"
#include "core/autodiff/tape.hpp"

namespace vivv {

// One function for each scalar vivv runs in.
template <template <class> class F>
struct PerScalar {
  F<double> in_double;
  F<long double> in_long_double;
  F<quad> in_quad;
  F<mpfr_real> in_mpfr;

  template <class T>
  const F<T>& get() const {
    if constexpr (std::is_same_v<T, double>) return in_double;
    else if constexpr (std::is_same_v<T, long double>) return in_long_double;
    else if constexpr (std::is_same_v<T, quad>) return in_quad;
    else return in_mpfr;
  }
};

template <class T>
using TapeVector = std::vector<TapeScalar<T>>;

// L(q, w) recorded with the case's parameters (name, decimal value).
template <class T>
using SystemRecorder = std::function<TapeScalar<T>(const TapeVector<T>& q, const TapeVector<T>& w,
                                                   const std::vector<std::pair<std::string, std::string>>& parameters)>;

// L_d(qb, qe; h) recorded, with the system's L(x, v) to call.
template <class T>
using DiscreteLagrangianRecorder = std::function<TapeScalar<T>(
    const TapeVector<T>& qb, const TapeVector<T>& qe, const TapeScalar<T>& h,
    const std::function<TapeScalar<T>(const TapeVector<T>&, const TapeVector<T>&)>& lagrangian)>;

struct RegisteredSystem {
  std::string name;
  int dimension;
  std::vector<std::pair<std::string, std::string>> parameters;  // name, default value
  std::shared_ptr<const PerScalar<SystemRecorder>> recorder;
};

struct RegisteredDiscreteLagrangian {
  std::string name;
  int order;  // the order its authors state: L_d = L_d^E + O(h^{r+1})
  std::shared_ptr<const PerScalar<DiscreteLagrangianRecorder>> recorder;
};

// The systems and discrete Lagrangians registered in this program, in order of registration.
inline std::vector<RegisteredSystem>& registered_systems() {
  static std::vector<RegisteredSystem> systems;
  return systems;
}

inline std::vector<RegisteredDiscreteLagrangian>& registered_discrete_lagrangians() {
  static std::vector<RegisteredDiscreteLagrangian> rules;
  return rules;
}

}  // namespace vivv
