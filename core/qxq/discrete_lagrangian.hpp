// Q×Q discrete Lagrangians L_d(q_b, q_e; h) and their Legendre transforms (docs/theory.md (Q × Q)).
//
// Arguments are named (begin, end); the paper writes L_h(q+, q−) with the
// later point first. Δ = q_e − q_b. The whole contract of a discrete
// Lagrangian is L_d, p_begin = −∂L_d/∂q_b and p_end = +∂L_d/∂q_e; the last two
// (and the Jacobians the DEL solver needs) come from automatic differentiation.
#pragma once

#include <algorithm>
#include <array>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/qxq/discrete_legendre.hpp"
#include "core/qxq/galerkin.hpp"
#include "core/qxq/sparse_legendre.hpp"
#include "core/autodiff/jet.hpp"
#include "core/lagrangian/lagrangian.hpp"
#include "core/autodiff/tape.hpp"

namespace vivv {

enum class QxQRule {
  left_rectangle,   // h·L(q_b, Δ/h)                       (paper §2, eq. 2.2 with a = 0)
  right_rectangle,  // h·L(q_e, Δ/h)
  midpoint,         // h·L((q_b + q_e)/2, Δ/h)
  trapezoid,        // h/2·[L(q_b, Δ/h) + L(q_e, Δ/h)]
  alpha,            // h·L((1 − α) q_b + α q_e, Δ/h)
  weighted,         // h·[(1 − β) L(q_b, Δ/h) + β L(q_e, Δ/h)]  (β = 1/2 is the trapezoid)
  expression,       // a formula in qb, qe, h and L(x, v), with the order its author claims
  galerkin,         // extremal of the quadrature action over degree-s curves (core/qxq/galerkin.hpp)
};

// Rule names as written in case files and reports, in the order of QxQRule.
inline const std::vector<std::string>& rule_names() {
  static const std::vector<std::string> names = {"left-rectangle", "right-rectangle", "midpoint", "trapezoid",
                                                 "alpha",          "weighted",        "expression",     "galerkin"};
  return names;
}
inline std::string rule_name(QxQRule rule) { return rule_names()[static_cast<int>(rule)]; }
// Inverse of rule_name; std::nullopt for an unknown name.
inline std::optional<QxQRule> rule_from_name(const std::string& name) {
  const auto& names = rule_names();
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<QxQRule>(i);
  return std::nullopt;
}

// The twin term + a·h^s·(q_e − q_b) of paper §2.2 (a ∈ R^n, s >= 1).
template <class T>
struct TwinTerm {
  std::vector<T> a;
  int power = 1;
};

// Whether any a_j of the twin term is nonzero (a = 0 is no twin term at all).
template <class T>
bool has_nonzero_coefficient(const TwinTerm<T>& twin) {
  for (const T& a : twin.a)
    if (a != 0) return true;
  return false;
}

// One Q×Q discrete Lagrangian: a rule, its parameter (α or β) and an optional twin term.
template <class T>
struct QxQDiscretization {
  QxQRule rule = QxQRule::midpoint;
  T parameter = T(1) / 2;  // α for `alpha`, β for `weighted`
  std::optional<TwinTerm<T>> twin;
  // `expression`: L_d recorded over (q_b, q_e, h) (core/formulas/formula_discretization.hpp), the
  // formula as written, and the order its author declares.
  std::shared_ptr<const Tape<T>> expression;
  // Its gradient and sparse Hessian over (q_b, q_e, h), for systems sized at run time
  // (core/qxq/sparse_legendre.hpp); null where nobody recorded them.
  std::shared_ptr<const SecondDerivativeTape<T>> expression_derivatives;
  std::string formula;
  int declared_order = 0;
  // `galerkin`: the curve degree, quadrature and its nodes and basis values, computed in T.
  std::shared_ptr<const GalerkinRule<T>> galerkin;

  // Order of the rule alone: 2 for the symmetric rules, 1 otherwise (MW Def. 2.3.1); for a
  // formula, the order its author claims (the prediction every order claim then checks).
  int rule_order() const {
    switch (rule) {
      case QxQRule::expression:
        return declared_order;
      case QxQRule::galerkin:
        return galerkin->spec.predicted_order();
      case QxQRule::midpoint:
      case QxQRule::trapezoid:
        return 2;
      case QxQRule::alpha:
      case QxQRule::weighted:
        return parameter == T(1) / 2 ? 2 : 1;
      default:
        return 1;
    }
  }

  // The points (c_k, f_k) of a rule that is h Σ_k c_k L((1 − f_k) q_b + f_k q_e, (q_e − q_b)/h);
  // empty for one that is not (an expression, Galerkin).
  std::vector<std::pair<T, T>> segment_points() const {
    switch (rule) {
      case QxQRule::left_rectangle: return {{T(1), T(0)}};
      case QxQRule::right_rectangle: return {{T(1), T(1)}};
      case QxQRule::midpoint: return {{T(1), T(1) / 2}};
      case QxQRule::alpha: return {{T(1), parameter}};
      case QxQRule::trapezoid: return {{T(1) / 2, T(0)}, {T(1) / 2, T(1)}};
      case QxQRule::weighted: return {{1 - parameter, T(0)}, {parameter, T(1)}};
      default: return {};
    }
  }

  // Order r of L_d: the rule's, lowered to s by a twin term, since a·h^s·(q_e − q_b) is
  // O(h^{s+1}) along solutions (paper §2.2). The map's order is the rule's: matched twin terms
  // cancel in the DEL.
  int nominal_order() const {
    if (!twin || !has_nonzero_coefficient(*twin)) return rule_order();
    return std::min(rule_order(), twin->power);
  }
};

// Whether two discretizations are the same rule (twin terms aside).
template <class T>
bool same_rule(const QxQDiscretization<T>& a, const QxQDiscretization<T>& b) {
  if (a.rule != b.rule) return false;
  if (a.rule == QxQRule::expression) return a.formula == b.formula;
  if (a.rule == QxQRule::galerkin)
    return a.galerkin->spec.degree == b.galerkin->spec.degree && a.galerkin->spec.lobatto == b.galerkin->spec.lobatto &&
           a.galerkin->spec.nodes == b.galerkin->spec.nodes;
  return a.rule != QxQRule::alpha && a.rule != QxQRule::weighted ? true : a.parameter == b.parameter;
}

// The same discretization without its twin term.
template <class T>
QxQDiscretization<T> without_twin(const QxQDiscretization<T>& d) {
  QxQDiscretization<T> plain;
  plain.rule = d.rule;
  plain.parameter = d.parameter;
  plain.expression = d.expression;
  plain.expression_derivatives = d.expression_derivatives;
  plain.formula = d.formula;
  plain.declared_order = d.declared_order;
  plain.galerkin = d.galerkin;
  return plain;
}

// L_d(q_b, q_e; h) evaluated in S (T or a jet over T).
template <LagrangianSystem System, class P>
auto discrete_lagrangian(const System& system,
                         const QxQDiscretization<typename System::Scalar>& discretization,
                         const P& q_b, const P& q_e, const typename System::Scalar& h) {
  using S = typename P::value_type;
  using T = typename System::Scalar;
  constexpr int N = System::dimension;
  const int n = static_cast<int>(q_b.size());
  Coordinates<S, N> velocity = make_point<S, N>(n), q_mid = make_point<S, N>(n);
  for (int i = 0; i < n; ++i) velocity[i] = (q_e[i] - q_b[i]) / h;
  const T& c = discretization.parameter;
  // L at the point a fraction f along the segment, at its time t_b + f·h (an L that depends on t;
  // t_b is the system's time).
  const T t_b = system_time(system);
  const bool timed = depends_on_time(system);
  auto at = [&](const T& fraction, const P& q) {
    return lagrangian_at(system, timed ? T(t_b + fraction * h) : t_b, q, velocity);
  };
  auto on_segment = [&](const T& fraction) {
    for (int i = 0; i < n; ++i) q_mid[i] = (1 - fraction) * q_b[i] + fraction * q_e[i];
    return at(fraction, q_mid);
  };
  S value = S(0);
  switch (discretization.rule) {
    case QxQRule::left_rectangle:
      value = h * at(T(0), q_b);
      break;
    case QxQRule::right_rectangle:
      value = h * at(T(1), q_e);
      break;
    case QxQRule::midpoint:
      value = h * on_segment(T(1) / 2);
      break;
    case QxQRule::alpha:
      value = h * on_segment(c);
      break;
    case QxQRule::trapezoid:
      value = h / 2 * (at(T(0), q_b) + at(T(1), q_e));
      break;
    case QxQRule::weighted:
      value = h * ((1 - c) * at(T(0), q_b) + c * at(T(1), q_e));
      break;
    case QxQRule::expression: {
      // Its inputs (q_b, q_e, h) and, for an L that depends on time, t_b.
      Coordinates<S, plus(twice(N), 2)> x = make_point<S, plus(twice(N), 2)>(discretization.expression->inputs);
      for (int i = 0; i < n; ++i) x[i] = q_b[i], x[n + i] = q_e[i];
      x[2 * n] = S(h);
      if (discretization.expression->inputs == 2 * n + 2) x[2 * n + 1] = S(t_b);
      value = discretization.expression->evaluate_first(x.data());
      break;
    }
    case QxQRule::galerkin:
      // Extremized by Newton in T: its derivatives come from discrete_legendre, not from jets.
      if constexpr (std::is_same_v<S, T>) {
        value = galerkin_legendre(system, *discretization.galerkin, as_vector<T, N>(q_b), as_vector<T, N>(q_e), h).value;
      } else {
        throw std::logic_error("a Galerkin L_d is evaluated in the working precision only (discrete_legendre gives "
                               "its derivatives)");
      }
      break;
  }
  if (discretization.twin) {
    using std::pow;
    T scale = pow(h, discretization.twin->power);
    for (int i = 0; i < n; ++i) value += scale * discretization.twin->a[i] * (q_e[i] - q_b[i]);
  }
  return value;
}

// L_d(q_b, q_e) as a jet of order `Order` in its 2n arguments (q_b first, then q_e); with
// Split = n, of the Hessian only the q_b–q_e block (core/autodiff/jet.hpp).
template <int Order, int Split = 0, LagrangianSystem System>
auto discrete_lagrangian_jet(const System& system,
                             const QxQDiscretization<typename System::Scalar>& discretization,
                             const VectorOf<System>& q_b, const VectorOf<System>& q_e,
                             const typename System::Scalar& h) {
  constexpr int N = System::dimension;
  const int n = static_cast<int>(q_b.size());
  using J = Jet<typename System::Scalar, twice(N), Order, N == any_size && Split ? any_size : Split>;
  Coordinates<J, N> jet_b = make_point<J, N>(n), jet_e = make_point<J, N>(n);
  for (int i = 0; i < n; ++i) {
    jet_b[i] = J::variable(q_b[i], i, 2 * n);
    jet_e[i] = J::variable(q_e[i], n + i, 2 * n);
  }
  return with_size(J(discrete_lagrangian(system, discretization, jet_b, jet_e, h)), 2 * n);
}

template <LagrangianSystem System>
auto discrete_legendre(const System& system,
                       const QxQDiscretization<typename System::Scalar>& discretization,
                       const VectorOf<System>& q_b, const VectorOf<System>& q_e,
                       const typename System::Scalar& h) {
  using T = typename System::Scalar;
  constexpr int N = System::dimension;
  const int n = static_cast<int>(q_b.size());
  if constexpr (SparselyDifferentiated<System>) {
    if (sparse_path_applies(system, discretization)) return sparse_discrete_legendre(system, discretization, q_b, q_e, h);
  }
  if (discretization.rule == QxQRule::galerkin) {
    // The envelope theorem and the Schur complement (core/qxq/galerkin.hpp); a twin term
    // a·h^s·(q_e − q_b) adds a·h^s to both momenta and nothing to their derivatives.
    DiscreteLegendre<T, N> d = galerkin_legendre(system, *discretization.galerkin, q_b, q_e, h);
    if (discretization.twin) {
      using std::pow;
      const T scale = pow(h, discretization.twin->power);
      for (int i = 0; i < n; ++i) {
        d.value += scale * discretization.twin->a[i] * (q_e[i] - q_b[i]);
        d.p_begin[i] += scale * discretization.twin->a[i];
        d.p_end[i] += scale * discretization.twin->a[i];
      }
    }
    return d;
  }
  const auto L = discrete_lagrangian_jet<2>(system, discretization, q_b, q_e, h);
  DiscreteLegendre<T, N> d(n);
  d.value = L.value;
  for (int i = 0; i < n; ++i) {
    d.p_begin[i] = -L.gradient[i];
    d.p_end[i] = L.gradient[n + i];
    for (int j = 0; j < n; ++j) {
      d.dp_begin_dq_b(i, j) = -L.second(i, j);
      d.dp_begin_dq_e(i, j) = -L.second(i, n + j);
      d.dp_end_dq_b(i, j) = L.second(n + i, j);
      d.dp_end_dq_e(i, j) = L.second(n + i, n + j);
    }
  }
  return d;
}

// What a DEL step's Newton solve reads at (q_b, q_e): p_begin and ∂p_begin/∂q_e. They come from
// a jet that keeps only the q_b–q_e block of the Hessian (1 + 2n + n² numbers instead of
// 1 + 2n + 4n², and n² second derivatives computed instead of n(2n + 1)), bit for bit
// discrete_legendre's.
template <class T, int n>
struct BeginMomentum {
  explicit BeginMomentum(int size) : p_begin(zero_vector<T, n>(size)), dp_begin_dq_e(zero_matrix<T, n, n>(size, size)) {}
  Vector<T, n> p_begin;
  Matrix<T, n, n> dp_begin_dq_e;
};

template <LagrangianSystem System>
auto begin_momentum(const System& system,
                    const QxQDiscretization<typename System::Scalar>& discretization,
                    const VectorOf<System>& q_b, const VectorOf<System>& q_e,
                    const typename System::Scalar& h) {
  using T = typename System::Scalar;
  constexpr int N = System::dimension;
  const int n = static_cast<int>(q_b.size());
  BeginMomentum<T, N> d(n);
  if (discretization.rule == QxQRule::galerkin) {
    DiscreteLegendre<T, N> full = discrete_legendre(system, discretization, q_b, q_e, h);
    d.p_begin = std::move(full.p_begin);
    d.dp_begin_dq_e = std::move(full.dp_begin_dq_e);
    return d;
  }
  const auto L = discrete_lagrangian_jet<2, N>(system, discretization, q_b, q_e, h);
  for (int i = 0; i < n; ++i) {
    d.p_begin[i] = -L.gradient[i];
    for (int j = 0; j < n; ++j) d.dp_begin_dq_e(i, j) = -L.second(i, n + j);
  }
  return d;
}

// L_d and its two discrete Legendre transforms at (q_b, q_e), without the second derivatives:
// a first-order jet (2n + 1 numbers instead of 1 + 2n + 4n²), the same momenta bit for bit as
// discrete_legendre's (a jet's gradient is never computed from its Hessian).
template <class T, int n>
struct DiscreteMomenta {
  explicit DiscreteMomenta(int size) : p_begin(zero_vector<T, n>(size)), p_end(zero_vector<T, n>(size)) {}
  T value;
  Vector<T, n> p_begin, p_end;
};

template <LagrangianSystem System>
auto discrete_momenta(const System& system,
                      const QxQDiscretization<typename System::Scalar>& discretization,
                      const VectorOf<System>& q_b, const VectorOf<System>& q_e,
                      const typename System::Scalar& h) {
  using T = typename System::Scalar;
  constexpr int N = System::dimension;
  const int n = static_cast<int>(q_b.size());
  DiscreteMomenta<T, N> d(n);
  if constexpr (SparselyDifferentiated<System>) {
    if (sparse_path_applies(system, discretization)) {
      const auto L = sparse_discrete_derivatives(system, discretization, q_b, q_e, h, SecondDerivatives::none);
      d.value = L.value, d.p_begin = -L.gradient.head(n), d.p_end = L.gradient.tail(n);
      return d;
    }
  }
  if (discretization.rule == QxQRule::galerkin) {
    const DiscreteLegendre<T, N> full = discrete_legendre(system, discretization, q_b, q_e, h);
    d.value = full.value, d.p_begin = full.p_begin, d.p_end = full.p_end;
    return d;
  }
  const auto L = discrete_lagrangian_jet<1>(system, discretization, q_b, q_e, h);
  d.value = L.value;
  for (int i = 0; i < n; ++i) {
    d.p_begin[i] = -L.gradient[i];
    d.p_end[i] = L.gradient[n + i];
  }
  return d;
}

// p_begin(q_b, q_e) = −∂L_d/∂q_b (paper: F−L_h).
template <LagrangianSystem System>
auto p_begin(const System& system, const QxQDiscretization<typename System::Scalar>& discretization,
             const VectorOf<System>& q_b, const VectorOf<System>& q_e,
             const typename System::Scalar& h) {
  return discrete_momenta(system, discretization, q_b, q_e, h).p_begin;
}

// p_end(q_b, q_e) = +∂L_d/∂q_e (paper: F+L_h).
template <LagrangianSystem System>
auto p_end(const System& system, const QxQDiscretization<typename System::Scalar>& discretization,
           const VectorOf<System>& q_b, const VectorOf<System>& q_e,
           const typename System::Scalar& h) {
  return discrete_momenta(system, discretization, q_b, q_e, h).p_end;
}

// discrete_legendre with its blocks sparse: from L's sparse derivatives where that path applies,
// else the dense blocks' nonzeros (Galerkin's extremal, a dense jet), for the probes of
// symplecticity, which need only the blocks' products with vectors.
template <LagrangianSystem System>
SparseLegendreBlocks<typename System::Scalar> legendre_blocks(
    const System& system, const QxQDiscretization<typename System::Scalar>& discretization,
    const VectorOf<System>& q_b, const VectorOf<System>& q_e, const typename System::Scalar& h) {
  if constexpr (SparselyDifferentiated<System>) {
    if (sparse_path_applies(system, discretization)) return sparse_legendre_blocks(system, discretization, q_b, q_e, h);
  }
  using T = typename System::Scalar;
  const auto dense = discrete_legendre(system, discretization, q_b, q_e, h);
  SparseLegendreBlocks<T> d;
  d.p_begin = dense.p_begin;
  d.p_end = dense.p_end;
  auto sparse = [n = static_cast<int>(q_b.size())](const auto& block) {
    std::vector<Eigen::Triplet<T>> entries;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        if (block(i, j) != 0) entries.emplace_back(i, j, block(i, j));
    Eigen::SparseMatrix<T> out(n, n);
    out.setFromTriplets(entries.begin(), entries.end());
    return out;
  };
  d.dp_begin_dq_b = sparse(dense.dp_begin_dq_b);
  d.dp_begin_dq_e = sparse(dense.dp_begin_dq_e);
  d.dp_end_dq_b = sparse(dense.dp_end_dq_b);
  d.dp_end_dq_e = sparse(dense.dp_end_dq_e);
  return d;
}

}  // namespace vivv
