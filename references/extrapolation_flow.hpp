// A high-order one-step reference integrator for any Lagrangian system:
// Gragg–Bulirsch–Stoer extrapolation with step-size and order control
// (Hairer–Nørsett–Wanner, Solving ODEs I, §II.9, the ODEX strategy).
//
// The Euler–Lagrange equations in first-order form y = (q, w),
//   q' = w,   w' = M⁻¹ (dL/dq − (d²L/dw dq) w)      (docs/theory.md),
// are advanced by steps H. Each step computes the modified-midpoint values
// T_{j,1} with n_j = 2j substeps (Gragg: an expansion in even powers of
// H/n_j) and extrapolates them to H/n → 0 by Aitken–Neville in h²:
//   T_{j,l+1} = T_{j,l} + (T_{j,l} − T_{j−1,l}) / ((n_j / n_{j−l})² − 1),
// an approximation of order 2j. A step is accepted when
//   max_i |T_{j,j} − T_{j,j−1}|_i / (tol_local (1 + max(|y_i|, |y_new_i|))) ≤ 1,
// an absolute-plus-relative test on the local error; the accepted value is
// the more accurate T_{j,j}. The number of columns adapts to the work per
// unit step (ODEX), up to max_columns: about ln(1/tol)/4 columns minimize the
// work, but T_{k,k} amplifies round-off by the Lebesgue constant Λ_k of the
// extrapolation (~10^{0.34 k} for this sequence), so the columns are capped
// where Λ_k ε would exceed 10⁴ tol. At 200 bits and tol 1e-56 that allows ~28
// columns; steps then use ~20 of them (order ~40).
//
// gragg_bulirsch_stoer controls the local error only. extrapolation_flow
// aims at a global error |y_i − y_i(t)| ≤ tol (1 + |y_i(t)|): it runs with
// tol_local = tol / 10⁶, room for the local errors of a hundred steps grown
// a thousandfold along the solution (at order ~40 the tighter local
// tolerance costs ~30% more steps); ReferenceFlow::estimate_error checks it.
//
// Nothing is returned silently: step-size underflow, too many steps and a
// tolerance below working precision throw, and the report says what was done.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/lagrangian/lagrangian.hpp"
#include "core/numerics/scalar.hpp"
#include "core/lagrangian/state.hpp"

namespace vivv {

template <class T>
struct ExtrapolationOptions {
  int max_columns = 0;                  // 0: chosen from the tolerance by default_max_columns
  long max_steps = 100000;              // accepted plus rejected steps
  int max_consecutive_rejections = 40;  // more means the tolerance is below the round-off floor
  T initial_step = 0;                   // 0: chosen from the vector field at the start
  T local_tolerance = 0;  // extrapolation_flow only; 0: local_tolerance_for(tolerance)
};

// What the integrator did.
struct ExtrapolationReport {
  long steps = 0;                 // accepted steps
  long rejected_steps = 0;        // steps redone with a smaller step size
  long function_evaluations = 0;  // evaluations of the vector field
  int max_columns = 0;            // columns available
  int highest_column = 0;         // most columns an accepted step used
};

template <class T, int d>
struct ExtrapolationSolution {
  Vector<T, d> y;
  ExtrapolationReport report;
};

template <class T, int n>
struct ExtrapolationFlowResult {
  State<T, n> state;
  ExtrapolationReport report;
};

// The smallest local tolerance gragg_bulirsch_stoer accepts: 100 ε.
template <class T>
T minimum_local_tolerance() {
  return 100 * epsilon<T>();
}

// Local tolerance extrapolation_flow uses for a global tolerance tol: tol / 10⁶.
template <class T>
T local_tolerance_for(const T& tol) {
  return tol / 1000000;
}

// The smallest global tolerance extrapolation_flow accepts: 10⁶ · 100 ε.
template <class T>
T minimum_flow_tolerance() {
  return 1000000 * minimum_local_tolerance<T>();
}

// log10 Λ_k, Λ_k = Σ_j Π_{i≠j} n_j² / |n_j² − n_i²| (n_i = 2i; i, j ≤ k): the factor by which
// T_{k,k} can amplify round-off in the T_{j,1}. A column-count heuristic, so double suffices.
inline double log10_extrapolation_lebesgue_constant(int k) {
  double sum = 0;
  for (int j = 1; j <= k; ++j) {
    double product = 1;
    for (int i = 1; i <= k; ++i) {
      if (i != j) product *= double(j * j) / std::abs(double(j * j - i * i));
    }
    sum += product;
  }
  return std::log10(sum);
}

// Columns for local tolerance tol: 1.5 ln(1/tol)/4 + 3 (ln(1/tol)/4 is optimal), within [6, 64],
// and no more than keep Λ_k ε ≤ 10⁴ tol, so that round-off cannot swamp the error estimate.
template <class T>
int default_max_columns(const T& tol) {
  using std::log10;
  const double log10_tol = static_cast<double>(log10(tol));
  const double log10_epsilon = static_cast<double>(log10(epsilon<T>()));
  int columns = std::clamp(static_cast<int>(1.5 * -log10_tol * 2.302585092994046 / 4) + 3, 6, 64);
  while (columns > 6 &&
         log10_extrapolation_lebesgue_constant(columns) + log10_epsilon > 4 + log10_tol) {
    --columns;
  }
  return columns;
}

namespace extrapolation_detail {

// Scaled error max_i |a_i − b_i| / (tol (1 + max(|y_i|, |b_i|))).
template <class T, int d>
T scaled_error(const Vector<T, d>& a, const Vector<T, d>& b, const Vector<T, d>& y, const T& tol) {
  using std::abs;
  using std::max;
  T error = 0;
  for (int i = 0; i < a.size(); ++i) {
    T scale = tol * (1 + max(abs(y[i]), abs(b[i])));
    error = max(error, T(abs(a[i] - b[i]) / scale));
  }
  return error;
}

// Whether every y_i is finite.
template <class T, int d>
bool all_finite(const Vector<T, d>& v) {
  using boost::multiprecision::isfinite;
  using std::isfinite;
  for (int i = 0; i < v.size(); ++i)
    if (!isfinite(v[i])) return false;
  return true;
}

}  // namespace extrapolation_detail

// y(t_end) for y' = f(y), y(0) = y0 (t_end of either sign), by GBS to local tolerance tol.
template <class T, int d, class F>
ExtrapolationSolution<T, d> gragg_bulirsch_stoer(F f, const Vector<T, d>& y0, const T& t_end,
                                                 const T& tol,
                                                 const ExtrapolationOptions<T>& options = {}) {
  using boost::multiprecision::isfinite;
  using std::abs;
  using std::isfinite;
  using std::log10;
  using std::max;
  using std::min;
  using std::pow;
  using Y = Vector<T, d>;

  if (!(tol >= minimum_local_tolerance<T>())) {
    throw std::invalid_argument("gragg_bulirsch_stoer: local tolerance " + to_decimal<T>(tol) +
                                " is below 100 ulps of " + scalar_name<T>() + " (" +
                                std::to_string(precision_bits<T>()) +
                                " bits); raise the precision");
  }
  if (!isfinite(t_end) || !extrapolation_detail::all_finite<T, d>(y0)) {
    throw std::invalid_argument("gragg_bulirsch_stoer: non-finite start or end time");
  }

  ExtrapolationSolution<T, d> solution{y0, {}};
  ExtrapolationReport& report = solution.report;
  const int max_columns = options.max_columns > 0 ? options.max_columns : default_max_columns(tol);
  if (max_columns < 3) throw std::invalid_argument("gragg_bulirsch_stoer: need at least 3 columns");
  report.max_columns = max_columns;
  if (t_end == 0) return solution;

  auto field = [&](const Y& y) {
    ++report.function_evaluations;
    return Y(f(y));
  };

  // Substeps n_j = 2j, and the work A_j = 1 + Σ_{i≤j} n_i of columns 1..j (index j − 1).
  std::vector<int> substeps(max_columns + 1);
  std::vector<T> work(max_columns + 1);
  for (int j = 1; j <= max_columns + 1; ++j) substeps[j - 1] = 2 * j;
  work[0] = T(substeps[0] + 1);
  for (int j = 1; j <= max_columns; ++j) work[j] = work[j - 1] + substeps[j];

  // Step-size controller constants (HNW's ODEX defaults), written in T.
  const T safety_1 = T(65) / 100, safety_2 = T(94) / 100;
  const T smallest_factor = T(2) / 100, largest_factor = T(4);
  const T work_decrease = T(8) / 10, work_increase = T(9) / 10;  // HNW I, §II.9

  const T direction = t_end > 0 ? T(1) : T(-1);
  T t = 0;
  Y y = y0;
  Y f0 = field(y);

  // Initial step: a quarter of the time scale min_i (1 + |y_i|) / |f_i|.
  T h = abs(options.initial_step);
  if (h == 0) {
    h = abs(t_end);
    for (int i = 0; i < y.size(); ++i)
      if (f0[i] != 0) h = min(h, T((1 + abs(y[i])) / abs(f0[i]) / 4));
  }
  h = min(h, abs(t_end));

  // Initial number of columns ODEX uses: 0.6 log10(1/tol) + 1.5.
  int k = static_cast<int>(static_cast<double>(-log10(tol)) * 0.6 + 1.5);
  k = std::clamp(k, 2, max_columns - 1);

  std::vector<Y> previous_row, row;
  std::vector<T> error(max_columns + 1, T(0)), optimal_step(max_columns + 1, T(0)),
      work_per_time(max_columns + 1, T(0));
  bool reject = false, first_or_last = true, last = false;
  int consecutive_rejections = 0;

  while (true) {
    const long taken = report.steps + report.rejected_steps;
    // Fail fast: after a thousand steps, a pace that would need more than the limit ends the
    // run now instead of after max_steps steps (minutes in MPFR).
    const bool projected_over = taken >= 1000 && t != 0 &&
                                static_cast<double>(abs(t_end / t)) * static_cast<double>(taken) > options.max_steps;
    if (taken >= options.max_steps || projected_over) {
      const double projected = t != 0 ? static_cast<double>(abs(t_end / t)) * static_cast<double>(taken) : 0;
      throw std::runtime_error(
          "the extrapolation (Gragg–Bulirsch–Stoer) flow would need " +
          (t != 0 ? "about " + to_decimal(projected, 2) : std::string("more than ") + std::to_string(taken)) +
          " steps to reach t = " + to_decimal<T>(t_end, 6) + " (" + std::to_string(taken) + " steps reached t = " +
          to_decimal<T>(t, 6) + ", tolerance " + to_decimal<T>(tol, 3) + "); its limit is " +
          std::to_string(options.max_steps) +
          ": the motion is too fast, or too long, for this T at this tolerance (take a smaller T)");
    }
    const T remaining = t_end - t;
    if (h <= 8 * epsilon<T>() * max(abs(t), abs(t_end))) {
      throw std::runtime_error(
          "the extrapolation (Gragg–Bulirsch–Stoer) flow's step fell to h = " + to_decimal<T>(h, 6) +
          " at t = " + to_decimal<T>(t, 17) + " on the way to " + to_decimal<T>(t_end, 17) + " (tolerance " +
          to_decimal<T>(tol, 3) + "): the solution is probably singular there (a collision, a blow-up, or a "
          "Lagrangian that stops being regular along it)");
    }
    if (h * T(101) / 100 >= abs(remaining)) {
      h = abs(remaining);
      last = true;
      first_or_last = true;
    }
    const T step = direction * h;

    // Column j (1-based): the midpoint value with n_j substeps, extrapolated; error_j from j ≥ 2.
    // Returns false when the midpoint rule left the domain of the vector field.
    auto compute_column = [&](int j) -> bool {
      const int substep_count = substeps[j - 1];
      const T small_step = step / substep_count;
      Y before = y;
      Y current = y + small_step * f0;
      try {
        for (int i = 1; i < substep_count; ++i) {
          Y next = before + 2 * small_step * field(current);
          before = std::move(current);
          current = std::move(next);
        }
      } catch (const SingularLagrangianError&) {
        return false;
      }
      if (!extrapolation_detail::all_finite<T, d>(current)) return false;
      row.resize(j);
      row[0] = current;
      for (int l = 1; l < j; ++l) {
        T ratio = T(substep_count) / substeps[j - 1 - l];
        row[l] = row[l - 1] + (row[l - 1] - previous_row[l - 1]) / (ratio * ratio - 1);
      }
      if (j >= 2) {
        error[j] = extrapolation_detail::scaled_error<T, d>(row[j - 1], row[j - 2], y, tol);
        const T exponent = T(1) / (2 * j - 1);
        const T factor_floor = pow(smallest_factor, exponent);
        T factor = pow(error[j] / safety_1, exponent) / safety_2;
        factor = min(largest_factor / factor_floor, max(factor_floor, factor));
        optimal_step[j] = h / factor;
        work_per_time[j] = work[j - 1] / optimal_step[j];
      }
      previous_row.swap(row);  // previous_row now holds row j
      return true;
    };

    // Run columns 1..j_max; stop early (accepted) when `accept_from` ≤ j and error_j ≤ 1.
    // Outcome: accepted with kc columns, or rejected.
    int kc = 0;
    bool accepted = false, domain_failure = false;
    auto run_columns = [&](int from, int to, int accept_from) {
      for (int j = from; j <= to; ++j) {
        if (!compute_column(j)) {
          domain_failure = true;
          return;
        }
        kc = j;
        if (j >= accept_from && j >= 2 && error[j] <= 1) {
          accepted = true;
          return;
        }
      }
    };

    if (first_or_last) {
      // First and last step: accept at the first column that converges.
      run_columns(1, k, 2);
      if (!accepted && !domain_failure && error[k] <= pow(T(substeps[k]) / substeps[0], 2)) {
        run_columns(k + 1, k + 1, k + 1);
      }
    } else {
      run_columns(1, k - 1, k + 2);  // compute only
      if (!domain_failure) {
        // Convergence monitor in column k − 1.
        bool hopeless = false;
        if (k - 1 >= 2 && !reject) {
          if (error[k - 1] <= 1) {
            accepted = true;
          } else {
            T bound = T(substeps[k]) * substeps[k - 1] / (substeps[0] * substeps[0]);
            hopeless = error[k - 1] > bound * bound;
          }
        }
        if (!accepted && !hopeless) {
          run_columns(k, k, k);
          // Hope for convergence in column k + 1.
          if (!accepted && !domain_failure && error[k] <= pow(T(substeps[k]) / substeps[0], 2)) {
            run_columns(k + 1, k + 1, k + 1);
          }
        }
      }
    }

    if (domain_failure) {
      // The midpoint rule left the domain of the vector field (e.g. |w| ≥ 1 for the
      // relativistic particle): halve the step and try again.
      ++report.rejected_steps;
      h /= 2;
      reject = true;
      last = false;
      continue;
    }

    if (!accepted) {
      ++report.rejected_steps;
      if (++consecutive_rejections > options.max_consecutive_rejections) {
        throw std::runtime_error("gragg_bulirsch_stoer: " + std::to_string(consecutive_rejections) +
                                 " rejected steps in a row at t = " + to_decimal<T>(t, 17) + " (h = " +
                                 to_decimal<T>(h, 6) + "): the local tolerance " + to_decimal<T>(tol, 3) +
                                 " is probably below the round-off floor of " + scalar_name<T>() +
                                 " at " + std::to_string(precision_bits<T>()) + " bits");
      }
      k = std::min({k, kc, max_columns - 1});
      if (k > 2 && work_per_time[k - 1] < work_per_time[k] * work_decrease) --k;
      h = optimal_step[k];
      reject = true;
      last = false;
      continue;
    }

    // Accepted with kc columns: y ← T_{kc,kc}.
    ++report.steps;
    consecutive_rejections = 0;
    report.highest_column = std::max(report.highest_column, kc);
    y = previous_row[kc - 1];
    if (last) {
      solution.y = y;
      return solution;
    }
    t += step;
    f0 = field(y);
    first_or_last = false;

    // Columns for the next step, by work per unit time (ODEX).
    int k_optimal;
    if (kc == 2) {
      k_optimal = std::min(3, max_columns - 1);
      if (reject) k_optimal = 2;
    } else if (kc <= k) {
      k_optimal = kc;
      if (work_per_time[kc - 1] < work_per_time[kc] * work_decrease) k_optimal = kc - 1;
      if (work_per_time[kc] < work_per_time[kc - 1] * work_increase)
        k_optimal = std::min(kc + 1, max_columns - 1);
    } else {
      k_optimal = kc - 1;
      if (kc > 3 && work_per_time[kc - 2] < work_per_time[kc - 1] * work_decrease)
        k_optimal = kc - 2;
      if (work_per_time[kc] < work_per_time[k_optimal] * work_increase)
        k_optimal = std::min(kc, max_columns - 1);
    }
    if (reject) {
      // After a rejection, neither the order nor the step grows.
      k = std::min(k_optimal, kc);
      h = min(h, optimal_step[k]);
      reject = false;
      continue;
    }
    if (k_optimal <= kc) {
      h = optimal_step[k_optimal];
    } else if (kc < k && work_per_time[kc] < work_per_time[kc - 1] * work_increase) {
      h = optimal_step[kc] * work[k_optimal] / work[kc - 1];
    } else {
      h = optimal_step[kc] * work[k_optimal - 1] / work[kc - 1];
    }
    k = k_optimal;
  }
}

// F_t(start) for q' = w, w' = euler_lagrange_acceleration(system, q, w), by GBS at local tolerance
// tol / 10⁶ (or options.local_tolerance when set).
template <LagrangianSystem System>
ExtrapolationFlowResult<typename System::Scalar, System::dimension> extrapolation_flow(
    const System& system, const State<typename System::Scalar, System::dimension>& start,
    const typename System::Scalar& t, const typename System::Scalar& tolerance,
    const ExtrapolationOptions<typename System::Scalar>& options = {}) {
  using T = typename System::Scalar;
  constexpr int N = System::dimension;
  const int n = static_cast<int>(start.q.size());
  using Y = Vector<T, twice(N)>;
  if (options.local_tolerance == 0 && !(tolerance >= minimum_flow_tolerance<T>())) {
    throw std::invalid_argument("extrapolation_flow: tolerance " + to_decimal<T>(tolerance) +
                                " is below 10⁸ ulps of " + scalar_name<T>() + " (" +
                                std::to_string(precision_bits<T>()) +
                                " bits), the floor for a local tolerance of 100 ulps");
  }
  const T local_tolerance =
      options.local_tolerance != 0 ? options.local_tolerance : local_tolerance_for(tolerance);
  auto euler_lagrange_field = [&system, n](const Y& y) {
    Vector<T, N> q = y.head(n), w = y.tail(n);
    Vector<T, N> acceleration = euler_lagrange_acceleration(system, q, w);  // may throw
    Y derivative(2 * n);
    derivative.head(n) = w;
    derivative.tail(n) = acceleration;
    return derivative;
  };
  Y y0(2 * n);
  y0.head(n) = start.q;
  y0.tail(n) = start.w;
  auto solution =
      gragg_bulirsch_stoer<T, twice(N)>(euler_lagrange_field, y0, t, local_tolerance, options);
  ExtrapolationFlowResult<T, N> result;
  result.state.q = solution.y.head(n);
  result.state.w = solution.y.tail(n);
  result.report = solution.report;
  return result;
}

}  // namespace vivv
