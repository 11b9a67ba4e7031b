// local-order: every one-step map of order r has local error
//   |Φ_h(x) − φ_h(x)| = O(h^(r+1))        (Hairer–Nørsett–Wanner I, Thm II.3.4; Marsden–West Thm 2.3.1)
// on (q, p), at several states x along the reference orbit — not only the initial one. It is the
// map's counterpart of lagrangian-order: one step, so no accumulation along the orbit and no
// cancellation between steps, and a small first-order term shows at once. Φ_h is the case's map:
// a program's (process), an odeint stepper, a user's map, or the DEL map (q, p) → (q', p') of a
// Q×Q rule (p_begin[L_d](q, q') = p, p' = p_end[L~_d](q, q')). On the paper's TQ discretizations
// the `order` claim (Thm 5.5) is this measurement, and a TQ case asks for that instead.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>

#include "harness/claims/claim.hpp"
#include "harness/claims/error_location.hpp"

namespace vivv {

struct MapLocalOrderClaim : Claim<MapLocalOrderClaim> {
  static constexpr const char* id = "local-order";
  // A DEL map's step from a state of the orbit at its own time t0 + t_j (CaseContext::at, exact_after).
  static constexpr bool takes_time_dependent_lagrangians = true;
  static constexpr const char* series_rules[] = {"order", "floor", "none"};
  static constexpr const char* source = "Hairer–Nørsett–Wanner I, Thm II.3.4; Marsden–West Thm 2.3.1";
  static constexpr const char* prediction =
      "one step of an order-r map from states along the reference orbit: |Φ_h(x) − φ_h(x)| = O(h^(r+1)) on (q, p)";

  // The states along the orbit, x(t_j) at t_j = j·T/states, and the most halvings of h below the
  // case's finest step: they go on until the error reaches the floor, as deep as precision-leak's
  // grid, so that a lower-order term too small for the case's steps (a 10⁻⁶ model error, a double
  // literal) shows where it outgrows the method's own error.
  static constexpr int states = 4;
  static constexpr int extra_halvings = 80;

  // r + 1, r the map's order; for a DEL map on (q, p) the order of its discrete Legendre
  // transforms, which a twin term a·h^s shifts by a·h^s (min(r, s): the map on Q×Q keeps r, its
  // representation on (q, p) does not), one less where the two sides differ (mismatched).
  template <LagrangianSystem System>
  static std::optional<int> theorem_order(const CaseContext<System>& context) {
    if (context.map || context.tq) return context.map_order() + 1;
    return std::max(1, context.lagrangian_order() - (context.scheme.mismatched ? 1 : 0)) + 1;
  }

  template <LagrangianSystem System>
  static void measure(const CaseContext<System>& context, ClaimResult& claim) {
    measure_to(context, claim, extra_halvings);
  }

  // The measurement with at most `halvings` halvings below the case's finest step (global-order
  // takes it 10 deep, harness/claims/global_order.hpp).
  template <LagrangianSystem System, class T = typename System::Scalar, int N = System::dimension>
  static void measure_to(const CaseContext<System>& context, ClaimResult& claim, int halvings) {
    using std::max;
    if (context.tq)
      throw CaseError(context.spec.file, "claims",
                      "local-order measures one step of a map; on a discretization of TQ that is the "
                      "claim \"order\" (paper Thm 5.5): list \"order\" instead");
    const OrderPrediction prediction = predicted(context);
    const std::string map_words = map_name(context);
    // The step sizes: the case's sweep, then halvings below its finest step to the floor.
    std::vector<T> steps = context.steps();
    for (int k = 0; k < halvings; ++k) steps.push_back(steps.back() / 2);
    nlohmann::json starts = nlohmann::json::array();
    std::vector<std::string> defect_times;  // the states whose step failed its order
    // Where the failing states' one-step errors sit (harness/claims/error_location.hpp): each
    // coordinate's squared error at the finest step of the fit, and the lowest fitted order seen.
    std::vector<double> defect_squared(static_cast<std::size_t>(context.n), 0.0);
    double lowest_defect_order = INFINITY;
    for (int j = 0; j < states; ++j) {
      const T t = context.final_time * T(j) / T(states);
      const State<T, N> x = j == 0 ? context.initial : context.reference.advance(context.initial, t);
      const bool timed = depends_on_time(context.system);
      const System at_x = timed ? context.at(t) : context.system;  // the system at x's time
      const Vector<T, N> p = momentum(at_x, x.q, x.w);
      T scale = nan_max(max_norm<T, N>(x.q), max_norm<T, N>(p));
      std::vector<T> error, used_h;
      std::vector<std::vector<double>> by_coordinate;  // per h (as used_h): each coordinate's error
      std::vector<double> last_by_coordinate;
      const auto measure = [&](const T& h) -> std::optional<T> {
        context.report("local-order: one step from x(" + format_scalar(t, 4) + ") at h = " + to_decimal<T>(h, 6));
        const State<T, N> exact = context.exact_after(x, t, h);
        const auto [q1, p1] = one_step(context, at_x, x, h);
        const Vector<T, N> p_exact = timed ? momentum(context.at(T(t + h)), exact.q, exact.w)
                                           : momentum(context.system, exact.q, exact.w);
        const T e = nan_max(max_norm<T, N>(Vector<T, N>(q1 - exact.q)), max_norm<T, N>(Vector<T, N>(p1 - p_exact)));
        using std::abs, std::isfinite;
        if (!isfinite(e)) return std::nullopt;
        last_by_coordinate.assign(q1.size(), 0.0);
        for (int i = 0; i < static_cast<int>(q1.size()); ++i)
          last_by_coordinate[i] = static_cast<double>(nan_max(T(abs(T(q1[i] - exact.q[i]))), T(abs(T(p1[i] - p_exact[i])))));
        scale = nan_max(scale, nan_max(max_norm<T, N>(Vector<T, N>(exact.q - x.q)), max_norm<T, N>(Vector<T, N>(p_exact - p))));
        return e;
      };
      for (const T& h : steps) {
        const std::optional<T> e = measure(h);
        if (!e) throw CaseError(context.spec.file, "steps", map_words + " left the finite numbers in one step of h = " +
                                                                format_scalar(h, 6) + ": increase the step counts");
        error.push_back(*e);
        used_h.push_back(h);
        by_coordinate.push_back(last_by_coordinate);
        // Halvings below the case's sweep stop at the floor: past it they only show rounding.
        if (used_h.size() > context.steps().size() && error.back() <= floor_at(context, scale, h, &x).value()) break;
      }
      // A high-order map in a short precision: where fewer than three errors clear the floor,
      // steps up to 8 times the case's largest bring the order back into view (while finite).
      for (int k = 0; k < 3; ++k) {
        const Floor<T> floor = floor_at(context, scale, used_h.back(), &x);
        const auto above = std::count_if(error.begin(), error.end(), [&](const T& e) { return e > floor.value(); });
        if (above >= 3) break;
        const T h = used_h.front() * 2;
        const std::optional<T> e = measure(h);
        if (!e) break;
        used_h.insert(used_h.begin(), h);
        error.insert(error.begin(), *e);
        by_coordinate.insert(by_coordinate.begin(), last_by_coordinate);
      }
      const Floor<T> floor = floor_at(context, scale, used_h.back(), &x);
      Series series = make_series("|Φ_h(x) − φ_h(x)| from x(" + format_scalar(t, 4) + ")", used_h, error, floor,
                                  std::optional<double>(prediction.order), prediction.exact,
                                  context.order_tolerance, context.fit_options);
      if (series.holds && !*series.holds && !series.inconclusive) {
        defect_times.push_back(format_scalar(t, 4));
        if (series.fit && series.fit->ok && !series.fit->used.empty()) {
          lowest_defect_order = std::min(lowest_defect_order, series.fit->order);
          int finest = series.fit->used.front();  // the used point of the smallest h
          for (const int k : series.fit->used)
            if (used_h[k] < used_h[finest]) finest = k;
          const std::vector<double>& errors = by_coordinate[finest];
          const double largest = *std::max_element(errors.begin(), errors.end());
          if (largest > 0 && std::isfinite(largest))
            for (std::size_t i = 0; i < errors.size() && i < defect_squared.size(); ++i)
              defect_squared[i] += (errors[i] / largest) * (errors[i] / largest);
        }
      }
      claim.series.push_back(std::move(series));
      nlohmann::json q_text = nlohmann::json::array(), p_text = nlohmann::json::array();
      for (int i = 0; i < static_cast<int>(x.q.size()); ++i) q_text.push_back(to_decimal<T>(x.q[i], 8)), p_text.push_back(to_decimal<T>(p[i], 8));
      starts.push_back({{"t", to_decimal<T>(t, 8)}, {"q", q_text}, {"p", p_text}});
    }
    claim.evidence["map"] = map_words;
    claim.evidence["states"] = starts;
    claim.evidence["local_order_r_plus_1"] = prediction.order;
    claim.evidence["grid"] = "the case's step sizes, then halvings below its finest until the error reaches "
                             "the floor (at most " + std::to_string(halvings) + "), and up to 3 doublings of its largest "
                             "where fewer than 3 errors clear the floor; each from " + std::to_string(states) +
                             " states x(j·T/" + std::to_string(states) + ") of the reference orbit";
    conclude(claim);
    record_answer_noise(context, claim, "the floor below which one step's error is not fitted");
    // What the failures mean, said once after them all (not once per state: a screen of repeats).
    if (claim.verdict == "fail" && !defect_times.empty()) {
      std::string times;
      for (const std::string& time : defect_times) times += (times.empty() ? "" : ", ") + time;
      claim.explanation += "; one step of " + map_words + (defect_times.size() == 1 ? " from the state at t = "
                                                                                    : " from the states at t = ") +
                           times + " is not of order " + std::to_string(prediction.order) +
                           ": an order defect, a lower-order term in " + map_words +
                           // precision-leak, which would name a narrower format, is refused for a
                           // program that computes in double: the text names only what the case accepts.
                           (context.spec.discretization.process_precision == "double"
                                ? std::string()
                                : std::string(" (where its size is a narrower format's rounding, precision-leak "
                                              "names the format)"));
      explain_location(context, claim, defect_squared, lowest_defect_order, map_words);
    }
  }

 private:
  // Where a failing step's error sits, and what an error of order about 1 means: a map whose one
  // step errs like h (global order 0) is consistent with another system than the case's. A wrong
  // method of the right system errs like h^(p+1) with p ≥ 1 however wrong its coefficients are;
  // an order below 1.5 says its vector field differs — masses, parameters, units or a force term
  // the program has and the case has not (or reads otherwise).
  template <LagrangianSystem System>
  static void explain_location(const CaseContext<System>& context, ClaimResult& claim,
                               const std::vector<double>& squared, double lowest_order, const std::string& map_words) {
    std::vector<std::string> names;
    if (context.spec.formula && context.spec.formula->coordinates.size() == squared.size()) {
      names = context.spec.formula->coordinates;
    } else {
      for (std::size_t i = 0; i < squared.size(); ++i) names.push_back("q[" + std::to_string(i + 1) + "]");
    }
    const ErrorLocation where = locate_error(squared, names);
    const std::string location = error_location_words(where);
    // Below 0.5 the one-step error does not vanish like h at all: no system's map errs so (a term
    // divided by h where it should be multiplied, a step size misread) — not "another system".
    const bool inconsistent = lowest_order < 0.5;
    const bool another_system = !inconsistent && lowest_order < 1.5;
    claim.evidence["error_location"] = {{"by_coordinate", where.by_coordinate},
                                        {"concentrated", where.concentrated},
                                        {"another_system", another_system},
                                        {"inconsistent", inconsistent},
                                        {"lowest_fitted_order", std::isfinite(lowest_order) ? nlohmann::json(lowest_order)
                                                                                           : nlohmann::json()}};
    if (another_system) {
      claim.explanation += ". One step errs like h^" + format_scalar(lowest_order, 3) +
                           " (global order about " + format_scalar(std::max(0.0, lowest_order - 1), 2) + "): " +
                           map_words + " steps another system than the case's — check its masses, parameters, "
                           "units and forces against the case's";
      if (!location.empty()) claim.explanation += "; the one-step error sits in " + location;
      if (context.map && context.spec.discretization.kind == "process")
        claim.explanation += " (the program's greeting carries the case's system and parameters: "
                             "docs/process-protocol.md)";
    } else if (inconsistent) {
      claim.explanation += ". One step errs like h^" + format_scalar(lowest_order, 3) + ": " + map_words +
                           " is not consistent with any system — its one-step error does not fall like h (a term "
                           "divided by h where it should be multiplied, a step size misread)";
      if (!location.empty()) claim.explanation += "; the one-step error sits in " + location;
    } else if (!location.empty()) {
      claim.explanation += "; the one-step error sits in " + location;
    }
  }

  // What the case's map is, in the words of the case.
  template <LagrangianSystem System>
  static std::string map_name(const CaseContext<System>& context) {
    if (context.map)
      return context.spec.discretization.kind == "process" ? "the program's map (" + context.map->name() + ")"
                                                            : "the map " + context.map->name();
    return context.scheme.mismatched ? "the mismatched DEL map" : "the DEL map of L_d";
  }

  // One step of the case's map from the state x at h, on (q, p); `system` is the case's at x's time
  // (the DEL map's segment starts there).
  template <LagrangianSystem System>
  static std::pair<VectorOf<System>, VectorOf<System>>
  one_step(const CaseContext<System>& context, const System& system,
           const State<typename System::Scalar, System::dimension>& x, const typename System::Scalar& h) {
    if (context.map) {
      // The map's clock at x's time (the system's: t0 + t); its answer's momentum at t + h.
      const typename System::Scalar t = system_time(system);
      context.map->set_time(t);
      const auto next = context.map->step(x, h);
      return {next.q, momentum(at_time(system, typename System::Scalar(t + h)), next.q, next.w)};
    }
    const auto q1 = start_from_momentum(system, context.scheme.future, x.q, x.w, h);
    return {q1, p_end(system, context.scheme.past, x.q, q1, h)};
  }

 public:
  // The floor of one step at h from a state of size `scale`: rounding of the step, which divides
  // differences of points by h in a DEL (ε·scale/h), a thousand times over; and the reference's
  // promised accuracy, a thousand times over. For a program that computes in double, judged from
  // a float128 side, the rounding is the program's own, measured at the state `at` (the spread r
  // of its answers, ProcessMap::answer_noise): 100·r, at least 10·ε·scale — a point there is
  // moved by 1 % at most, an order by 0.015. A NumPy RK4 on Kepler followed h⁵ down to 1.7e-16
  // while the fixed floor (1000·ε·scale/h, 2.4e-9 with a double reference) left it 3 points.
  template <LagrangianSystem System>
  static Floor<typename System::Scalar> floor_at(const CaseContext<System>& context,
                                                 const typename System::Scalar& scale,
                                                 const typename System::Scalar& h,
                                                 const State<typename System::Scalar, System::dimension>* at = nullptr) {
    using T = typename System::Scalar;
    using std::max;
    Floor<T> floor;
    const T per_step = T(1) / h;
    floor.rounding = T(1000) * context.working_epsilon() * scale * per_step;
    if (const auto noise = at && context.map ? context.map->answer_noise(*at, h) : std::nullopt)
      floor.rounding = max(T(100) * *noise, T(10) * context.working_epsilon() * scale);
    floor.reference = T(1000) * context.reference.tolerance() * scale;
    floor.scale = static_cast<long double>(scale);
    floor.n_max = static_cast<long double>(per_step);
    floor.precision_fixed = context.spec.discretization.process_precision == "double";
    return floor;
  }
};

}  // namespace vivv
