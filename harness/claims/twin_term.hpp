// Claims about the twin term a·h^s·(q_e − q_b) of paper §2:
//   twin-term-invariance: it cancels in the DEL — trajectories with and without
//     it are identical to working precision — while it shifts both discrete
//     Legendre transforms by exactly a·h^s (paper §2.3).
//   mismatched-legendre: in a mismatched DEL (L_d with a, L~_d with ã, or two
//     different rules) it no longer cancels: the order drops to r − 1, and for
//     r = 1 the scheme is inconsistent, converging at order 1 to the solution
//     of the modified equation of docs/theory.md (twin terms) (core/qxq/modified_equation.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <map>

#include "core/qxq/modified_equation.hpp"
#include "harness/claims/global_order.hpp"

namespace vivv {

// What twin-term-invariance measures at one h: the largest difference between
// the trajectories with and without the twin term, and the error of the
// Legendre transforms' shift against a·h^s, each with its tolerance.
template <class T>
struct TwinMeasurement {
  int N;
  T h, gap, trajectory_tolerance, shift, shift_error, shift_tolerance;
};

// max_j |(p_with − p_plain)_j − a_j h^s| over both transforms, and the size max_j |p_plain| + |a_j h^s|
// (at least 1) that its rounding is measured against.
template <class T, class Transform>
std::pair<T, T> legendre_shift_error(const Transform& with, const Transform& plain, const Transform& with_other,
                                     const Transform& plain_other, const TwinTerm<T>& twin, const T& h) {
  using std::abs, std::max, std::pow;
  T error = 0, scale = 1;
  for (std::size_t j = 0; j < twin.a.size(); ++j) {
    T expected_shift = twin.a[j] * pow(h, twin.power);
    error = nan_max(error, abs(with[j] - plain[j] - expected_shift));
    error = nan_max(error, abs(with_other[j] - plain_other[j] - expected_shift));
    scale = nan_max(scale, abs(plain[j]) + abs(expected_shift));
  }
  return {error, scale};
}

// One h's measurement from the two runs' gap and scale and the Legendre transforms with and
// without the twin term, with the rounding allowances of Q×Q and TQ alike: the trajectories
// 1024·N ulps of their size (N Newton solves, each converged to 64 ulps), the shift 64 ulps.
template <class T, class Transform>
TwinMeasurement<T> twin_measurement(int N, const T& h, const T& gap, const T& scale, const Transform& with,
                                    const Transform& plain, const Transform& with_other,
                                    const Transform& plain_other, const TwinTerm<T>& twin) {
  using std::pow;
  auto [shift_error, p_scale] = legendre_shift_error<T>(with, plain, with_other, plain_other, twin, h);
  return {N, h, gap, 1024 * T(N) * epsilon<T>() * scale, T(twin.a[0] * pow(h, twin.power)), shift_error,
          64 * epsilon<T>() * p_scale};
}

struct TwinTermInvarianceClaim : Claim<TwinTermInvarianceClaim> {
  static constexpr const char* id = "twin-term-invariance";
  // The DEL runs step at their own times; the Legendre shift is read on the last segment's system.
  static constexpr bool takes_time_dependent_lagrangians = true;
  static constexpr const char* series_rules[] = {"per-step-tolerance"};
  static constexpr const char* source = "paper §2.2–2.3";
  static constexpr const char* prediction =
      "trajectories with the twin term a·h^s·(end − begin) and without it are identical to "
      "working precision; both Legendre transforms shift by exactly a·h^s";

  template <LagrangianSystem System, class T = typename System::Scalar, int N = System::dimension>
  static void measure(const CaseContext<System>& context, ClaimResult& claim) {
    PerStepCheck<T> check;
    // The trajectory difference is the measured value; the Legendre shift is checked beside it.
    for (const auto& m : context.tq ? measure_tq(context) : measure_qxq(context))
      check.add(m.h, m.gap, m.trajectory_tolerance,
                {{"N", m.N},
                 {"legendre_shift", to_decimal<T>(m.shift)},
                 {"legendre_shift_error", to_decimal<T>(m.shift_error)},
                 {"legendre_shift_tolerance", to_decimal<T>(m.shift_tolerance)}},
                m.shift_error <= m.shift_tolerance);
    claim.evidence["formalism"] = context.tq ? "tq" : "qxq";
    check.conclude_claim(claim, context, context.tq ? "max_k |v_k(a) − v_k(0)|" : "max_k |q_k(a) − q_k(0)|",
                         "trajectories identical to working precision at every h",
                         "the twin term changed the trajectory or the Legendre shift is not a·h^s");
  }

 private:
  // Q×Q: the DEL with and without a·h^s·(q_e − q_b); p_begin and p_end at the last segment.
  template <LagrangianSystem System>
  static std::vector<TwinMeasurement<typename System::Scalar>> measure_qxq(const CaseContext<System>& context) {
    using T = typename System::Scalar;
    constexpr int N = System::dimension;
    using std::max;
    DelScheme<T> plain{without_twin(context.scheme.future), without_twin(context.scheme.past),
                       context.scheme.mismatched};
    SweepRun<System> with = run_sweep(context, context.scheme, true);
    SweepRun<System> without = run_sweep(context, plain, true);
    const auto& twin = *context.scheme.future.twin;
    std::vector<T> steps = context.steps();
    std::vector<TwinMeasurement<T>> measured;
    for (std::size_t i = 0; i < steps.size(); ++i) {
      const T& h = steps[i];
      int steps = context.step_counts()[i];
      T gap = 0, scale = 1;
      for (int k = 0; k <= steps; ++k) {
        gap = nan_max(gap, max_norm<T, N>(with.trajectories[i]->q[k] - without.trajectories[i]->q[k]));
        scale = nan_max(scale, max_norm<T, N>(with.trajectories[i]->q[k]));
      }
      // The Legendre shift at the run's last segment: exact up to a few roundings.
      const auto& q = without.trajectories[i]->q;
      const System last = context.at_step(h, steps - 1);  // the last segment starts at t0 + (N − 1)·h
      auto shifted = discrete_legendre(last, context.scheme.future, q[steps - 1], q[steps], h);
      auto plain_legendre = discrete_legendre(last, plain.future, q[steps - 1], q[steps], h);
      measured.push_back(twin_measurement(steps, h, gap, scale, shifted.p_begin, plain_legendre.p_begin,
                                          shifted.p_end, plain_legendre.p_end, twin));
    }
    return measured;
  }

  // TQ: F_h with and without a·h^s·(d+(v) − d−(v)) in L_h; P+ and P− at the last state.
  // With a past_discretization the steps with the twin term are mismatched (past at v,
  // the discretization at ṽ): the negative control, where the terms no longer cancel.
  template <LagrangianSystem System>
  static std::vector<TwinMeasurement<typename System::Scalar>> measure_tq(const CaseContext<System>& context) {
    using T = typename System::Scalar;
    constexpr int N = System::dimension;
    using std::max;
    const TQDiscretization<T>& with = *context.tq;
    const TQDiscretization<T>& with_past = context.tq_past ? *context.tq_past : with;
    TQDiscretization<T> plain = with;
    plain.twin.reset();
    const auto& twin = *with.twin;
    std::vector<T> steps = context.steps();
    std::vector<TwinMeasurement<T>> measured;
    for (std::size_t i = 0; i < steps.size(); ++i) {
      const T& h = steps[i];
      int steps = context.step_counts()[i];
      context.report("twin-term-invariance: " + std::to_string(steps) + " TQ steps with and without the twin term");
      // With the twin term and no past_discretization this is the case's own TQ sweep.
      const auto a = context.tq_past
                         ? std::make_shared<const std::vector<State<T, N>>>(tq_trajectory(
                               context.system, with_past, with, context.initial, h, steps))
                         : shared_tq_trajectory(context, h, steps);
      const auto b = tq_trajectory(context.system, plain, context.initial, h, steps);
      T gap = 0, scale = 1;
      for (int k = 0; k <= steps; ++k) {
        gap = nan_max(gap, state_distance((*a)[k], b[k]));
        scale = nan_max(scale, nan_max(max_norm<T, N>((*a)[k].q), max_norm<T, N>((*a)[k].w)));
      }
      auto v = tangent_point(b[steps]);
      auto shifted = tq_legendre(context.system, with, v, h);
      auto plain_legendre = tq_legendre(context.system, plain, v, h);
      measured.push_back(twin_measurement(steps, h, gap, scale, shifted.p_minus, plain_legendre.p_minus,
                                          shifted.p_plus, plain_legendre.p_plus, twin));
    }
    return measured;
  }
};

// The mismatch of a DEL whose future side carries a·h^s and whose past side
// ã·h^s̃ (either may be absent): p_begin − p_end is shifted by
// a·h^s − ã·h^s̃, so the force by (a·h^s − ã·h^s̃)/h (docs/theory.md (twin terms)). `power` is the
// lowest power with a nonzero net coefficient and `coefficient` that vector;
// no power when the two twin terms are identical — no mismatch at all.
template <class T>
struct TwinMismatch {
  std::optional<int> power;
  std::vector<T> coefficient;
};

template <class T>
TwinMismatch<T> twin_mismatch(const std::optional<TwinTerm<T>>& future, const std::optional<TwinTerm<T>>& past,
                              int dimension) {
  std::map<int, std::vector<T>> net;  // power -> a − ã at that power
  auto add = [&](const std::optional<TwinTerm<T>>& twin, int sign) {
    if (!twin) return;
    auto& c = net.try_emplace(twin->power, std::vector<T>(dimension, T(0))).first->second;
    for (int i = 0; i < dimension; ++i) c[i] += sign * twin->a[i];
  };
  add(future, 1);
  add(past, -1);
  for (const auto& [power, c] : net)
    if (std::any_of(c.begin(), c.end(), [](const T& x) { return x != 0; })) return {power, c};
  return {};
}

struct MismatchedLegendreClaim : Claim<MismatchedLegendreClaim> {
  static constexpr const char* id = "mismatched-legendre";
  static constexpr const char* series_rules[] = {"order", "floor", "none", "does-not-converge"};
  static constexpr const char* source = "paper §2.3";
  static constexpr const char* prediction =
      "the mismatched DEL p_begin[L_d] = p_end[L~_d] loses what the mismatch costs: twin terms "
      "a·h^s vs ã·h^s̃ whose difference starts at h^m shift the force by O(h^{m−1}) (order "
      "min(r, m − 1)), different rules by O(h^{r−1}); at order 0 it is inconsistent and, for "
      "m = 1, converges at order 1 to the modified equation L − (a − ã)·q";

  // The order §1.4 predicts against the original equation: min(r, m − 1) for a
  // twin mismatch first nonzero at power m, r − 1 for two different rules, r
  // when there is no mismatch at all; 0 means inconsistent.
  template <LagrangianSystem System>
  static int mismatch_order(const CaseContext<System>& context) {
    const auto& future = context.scheme.future;
    const auto& past = context.scheme.past;
    const int r = context.map_order();
    const bool same = same_rule(future, past);
    int order = same ? r : r - 1;
    auto mismatch = twin_mismatch(future.twin, past.twin, dimension_of(context.system));
    if (mismatch.power) order = std::min(order, *mismatch.power - 1);
    return std::max(order, 0);
  }

  // The order of convergence to the original solution; none when the scheme is inconsistent.
  template <LagrangianSystem System>
  static std::optional<int> theorem_order(const CaseContext<System>& context) {
    int order = mismatch_order(context);
    if (order == 0) return std::nullopt;
    return order;
  }

  template <LagrangianSystem System, class T = typename System::Scalar, int N = System::dimension>
  static void measure(const CaseContext<System>& context, ClaimResult& claim) {
    const auto& future = context.scheme.future;
    const auto& past = context.scheme.past;
    const bool same = same_rule(future, past);
    const auto mismatch = twin_mismatch(future.twin, past.twin, dimension_of(context.system));
    const int order = mismatch_order(context);
    claim.evidence["predicted_order_vs_original"] = order;
    claim.evidence["same_rule"] = same;
    claim.evidence["twin_mismatch_power"] = mismatch.power ? nlohmann::json(*mismatch.power) : nlohmann::json();
    SweepRun<System> run = run_sweep(context, context.scheme);
    const State<T, N>& final_state = context.final_state;
    std::vector<T> error;
    for (const auto& q : run.q_final) error.push_back(max_norm<T, N>(q - final_state.q));
    if (order >= 1) {
      claim.series.push_back(sweep_series(context, "|q_N − q(T)| (original equation)", error, predicted(context)));
      conclude(claim);
      return;
    }
    // Inconsistent: the error against the original solution must not vanish…
    Series original = sweep_series(context, "|q_N − q(T)| (original equation)", error, std::nullopt);
    bool stalls = original.fit && original.fit->ok && original.fit->order < 0.5;
    original.rule = "does-not-converge";
    original.holds = stalls;
    original.explanation = stalls ? "the error does not vanish as h → 0 (fitted order " +
                                        format_scalar(original.fit->order, 3) + " < 1/2)"
                                  : "the error vanishes as h → 0: the scheme is consistent";
    claim.series.push_back(original);
    if (!same || !mismatch.power || *mismatch.power != 1) {
      claim.explanation = "inconsistent; no modified equation is predicted for this mismatch";
      conclude(claim);
      return;
    }
    // …and the scheme converges at order 1 to L_mod = L − c·q, c the net coefficient of h¹;
    // the higher powers of the mismatch perturb the force by O(h).
    ForceShifted<System> modified{context.system, {}};
    nlohmann::json shift = nlohmann::json::array();
    for (int i = 0; i < dimension_of(context.system); ++i) {
      modified.c.push_back(mismatch.coefficient[i]);
      shift.push_back(to_decimal<T>(modified.c.back()));
    }
    claim.evidence["modified_lagrangian"] = "L_mod(q, w) = L(q, w) − c·q, c = a − ã at power 1";
    claim.evidence["c"] = shift;
    context.report("mismatched-legendre: modified reference flow");
    TaylorReference<ForceShifted<System>> modified_flow(
        modified, reference_tolerance_for<T>(context.spec.digits));
    State<T, N> modified_final = modified_flow.advance(context.initial, context.final_time);
    claim.evidence["modified_solution_q_T"] = to_decimal<T>(modified_final.q[0]);
    claim.evidence["original_solution_q_T"] = to_decimal<T>(final_state.q[0]);
    std::vector<T> modified_error;
    for (const auto& q : run.q_final) modified_error.push_back(max_norm<T, N>(q - modified_final.q));
    // The convergence to the modified solution is the claim's main measurement.
    claim.series.insert(claim.series.begin(),
                        sweep_series(context, "|q_N − q_mod(T)| (modified equation)", modified_error,
                                     OrderPrediction{1, false}));
    conclude(claim);
  }
};

}  // namespace vivv
