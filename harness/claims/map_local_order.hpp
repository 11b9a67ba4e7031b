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

namespace vivv {

struct MapLocalOrderClaim : Claim<MapLocalOrderClaim> {
  static constexpr const char* id = "local-order";
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
    for (int j = 0; j < states; ++j) {
      const T t = context.final_time * T(j) / T(states);
      const State<T, N> x = j == 0 ? context.initial : context.reference.advance(context.initial, t);
      const Vector<T, N> p = momentum(context.system, x.q, x.w);
      T scale = nan_max(max_norm<T, N>(x.q), max_norm<T, N>(p));
      std::vector<T> error, used_h;
      const auto measure = [&](const T& h) -> std::optional<T> {
        context.report("local-order: one step from x(" + format_scalar(t, 4) + ") at h = " + to_decimal<T>(h, 6));
        const State<T, N> exact = context.reference.advance(x, h);
        const auto [q1, p1] = one_step(context, x, h);
        const Vector<T, N> p_exact = momentum(context.system, exact.q, exact.w);
        const T e = nan_max(max_norm<T, N>(Vector<T, N>(q1 - exact.q)), max_norm<T, N>(Vector<T, N>(p1 - p_exact)));
        using std::isfinite;
        if (!isfinite(e)) return std::nullopt;
        scale = nan_max(scale, nan_max(max_norm<T, N>(Vector<T, N>(exact.q - x.q)), max_norm<T, N>(Vector<T, N>(p_exact - p))));
        return e;
      };
      for (const T& h : steps) {
        const std::optional<T> e = measure(h);
        if (!e) throw CaseError(context.spec.file, "steps", map_words + " left the finite numbers in one step of h = " +
                                                                format_scalar(h, 6) + ": increase the step counts");
        error.push_back(*e);
        used_h.push_back(h);
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
      }
      const Floor<T> floor = floor_at(context, scale, used_h.back(), &x);
      Series series = make_series("|Φ_h(x) − φ_h(x)| from x(" + format_scalar(t, 4) + ")", used_h, error, floor,
                                  std::optional<double>(prediction.order), prediction.exact,
                                  context.order_tolerance, context.fit_options);
      if (series.holds && !*series.holds && !series.inconclusive) defect_times.push_back(format_scalar(t, 4));
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
    }
  }

 private:
  // What the case's map is, in the words of the case.
  template <LagrangianSystem System>
  static std::string map_name(const CaseContext<System>& context) {
    if (context.map)
      return context.spec.discretization.kind == "process" ? "the program's map (" + context.map->name() + ")"
                                                            : "the map " + context.map->name();
    return context.scheme.mismatched ? "the mismatched DEL map" : "the DEL map of L_d";
  }

  // One step of the case's map from the state x at h, on (q, p).
  template <LagrangianSystem System>
  static std::pair<VectorOf<System>, VectorOf<System>>
  one_step(const CaseContext<System>& context, const State<typename System::Scalar, System::dimension>& x,
           const typename System::Scalar& h) {
    if (context.map) {
      const auto next = context.map->step(x, h);
      return {next.q, momentum(context.system, next.q, next.w)};
    }
    const auto q1 = start_from_momentum(context.system, context.scheme.future, x.q, x.w, h);
    return {q1, p_end(context.system, context.scheme.past, x.q, q1, h)};
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
