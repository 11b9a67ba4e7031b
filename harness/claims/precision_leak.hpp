// precision-leak: a method computed in a precision must be accurate to that precision. Its
// relative local defect
//   ρ(h) = |Φ_h(x_0) − F_h(x_0)| / |F_h(x_0) − x_0|        (on (q, p), max norms)
// is C·h^r from truncation plus rounding of size ε/h (ε/h² for a DEL, whose momenta divide
// differences of points by h). A quantity that passed through a lower precision (a double
// literal in a coefficient, a double-only function) adds a term δ·h^k, k < r, with δ the size
// of what was lost (about 2^-53 for a double): it does not depend on the working precision.
// The claim measures ρ on one h grid at the case's precision (d digits) and at 2d digits,
// everything — system, method, reference — rebuilt from the case file at 2d, and holds when
//   1. the floor min_h ρ falls by at least half of the (2d − d)·r/(r+2) digits rounding
//      predicts (a leak of order 0 leaves it where it was), and
//   2. above a thousand times the finer floor, where rounding is negligible, the finer defect
//      keeps its order: every pairwise order at least r − order_tolerance (a leak of order
//      k < r shows as order k there, below where the case's own precision could see it).
// A leak is flagged with δ = ρ/h^k at the smallest such h and the bits it corresponds to,
// −log2 δ. Negative control: Boost.Odeint's symplectic_rkn_sb3a_mclachlan, two of whose
// coefficients are double literals, in MPFR.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <type_traits>

#include "cases/catalogue.hpp"
#include "harness/claims/claim.hpp"

namespace vivv {

// The case's system built anew from its case file at the current MPFR precision (a system
// built at another precision keeps that precision's parameters): a catalogue system as its
// formula twin, as every case runs it (harness/run/run_case.cpp).
template <class T, int N>
FormulaSystem<T, N> system_at_current_precision(const CaseSpec& spec, const FormulaSystem<T, N>&) {
  // At the case's t0, as run_case puts the case's system (an L that depends on time).
  return at_time(make_formula_system<T, N>(spec.formula ? *spec.formula : catalogue_twin(spec.system, spec.parameters)),
                 from_decimal<T>(spec.start_time));
}

struct PrecisionLeakClaim : Claim<PrecisionLeakClaim> {
  static constexpr const char* id = "precision-leak";
  // One DEL step from x0 on [t0, t0 + h], p(h) read at t0 + h; the 2d-digit system is at t0 too.
  static constexpr bool takes_time_dependent_lagrangians = true;
  static constexpr const char* series_rules[] = {"none"};
  static constexpr const char* source = "round-off analysis of a one-step method (Higham, Accuracy and Stability "
                                        "of Numerical Algorithms, ch. 2)";
  static constexpr const char* prediction =
      "the floor of the relative local defect min_h |Φ_h(x0) − F_h(x0)| / |F_h(x0) − x0| falls with the "
      "precision, from d to 2d digits by at least half the d·r/(r+2) digits rounding predicts, and above the "
      "2d-digit floor the defect keeps its order r";
  // The order r of the relative defect: the method's (that of its global error), or the order
  // the case declares for this claim.
  static constexpr bool fails_by_order = false;  // a leak is a floor that does not fall

  template <LagrangianSystem System>
  static std::optional<int> theorem_order(const CaseContext<System>& context) {
    return context.map_order();
  }

  // Points per factor of 10 in h, and how far past the finer precision's expected floor the grid
  // reaches (a factor 10^margin in h), so that both minima lie inside it.
  static constexpr int points_per_decade = 2;
  static constexpr int margin_decades = 2;
  // The formats a quantity can leak through, by their significand bits: a lower-order term whose
  // size is within 2^8 of one of their unit roundoffs is a leak naming it; any other is an order
  // defect of the method itself, which precision-leak leaves to local-order (it passes, saying so).
  struct Format {
    const char* name;
    int bits;
  };
  static constexpr Format narrower_formats[] = {
      {"float", 24}, {"double", 53}, {"long double (x87)", 64}, {"float128", 113}};
  static constexpr double format_window_bits = 8;

  template <LagrangianSystem System, class T = typename System::Scalar, int N = System::dimension>
  static void measure(const CaseContext<System>& context, ClaimResult& claim) {
    if constexpr (!is_mpfr_v<T>) {
      throw CaseError(context.spec.file, "claims", "precision-leak compares two MPFR precisions: it needs "
                                                   "\"scalar\": \"mpfr\"");
    } else {
      const int digits = context.spec.digits, finer_digits = 2 * digits;
      if (finer_digits > 2000)
        throw CaseError(context.spec.file, "digits", "precision-leak runs the case again at twice its digits, and " +
                                                         std::to_string(digits) + " would make that more than 2000");
      const int r = predicted(context).order;
      const int points = grid_points(context, finer_digits, r);
      const Profile coarse = profile(context, points, digits);
      Profile fine;
      {
        PrecisionGuard guard(finer_digits);
        CaseSpec spec = context.spec;
        spec.digits = finer_digits;
        const CaseContext<System> finer(spec, system_at_current_precision(spec, context.system), context.progress);
        fine = profile(finer, points, finer_digits);
      }
      // 1. The floor falls.
      const double predicted_fall = (finer_digits - digits) * double(r) / (r + 2);
      const double fall = coarse.log10_floor - fine.log10_floor;
      const bool floor_falls = fall >= predicted_fall / 2;
      // 2. The finer defect keeps its order above its floor.
      const OrderKept kept = order_kept(fine, r, context.order_tolerance);
      claim.series.push_back(coarse.series);
      claim.series.push_back(fine.series);
      claim.evidence["digits"] = {digits, finer_digits};
      claim.evidence["floors"] = {coarse.floor, fine.floor};
      claim.evidence["order_r"] = r;
      claim.evidence["predicted_fall_digits"] = format_scalar(predicted_fall, 4);
      claim.evidence["observed_fall_digits"] = format_scalar(fall, 4);
      claim.evidence["finer_pairwise_orders"] = kept.orders;
      claim.evidence["grid"] = "h = h_min · 10^(-k/" + std::to_string(points_per_decade) +
                               "), h_min the case's smallest step, to " + std::to_string(margin_decades) +
                               " decades past 10^(-2d/(r+1)); floor: the smallest max of two neighbouring defects";
      const std::string floors = "the defect's floor is " + coarse.floor + " with " +
                                 std::to_string(digits) + " digits and " + fine.floor + " with " +
                                 std::to_string(finer_digits) + " (it fell " + format_scalar(fall, 3) +
                                 " digits of the " + format_scalar(predicted_fall, 3) +
                                 " rounding predicts; a floor that is rounding falls by at least half, " +
                                 format_scalar(predicted_fall / 2, 3) + ")";
      if (floor_falls && kept.holds) {
        claim.verdict = "pass";
        claim.explanation = floors + ", and above it the defect keeps order " + std::to_string(r);
      } else if (const auto& leaked = format_of(leak_bits(kept, fine)); !leaked) {
        // A lower-order term of no narrower format's size: the method's own order defect.
        const int k = kept.holds ? 0 : std::max(0, static_cast<int>(std::lround(kept.leak_order)));
        claim.evidence["order_defect"] = true;
        claim.evidence["leak_bits"] = format_scalar(leak_bits(kept, fine), 4);
        claim.verdict = "pass";
        claim.explanation =
            "no precision leak (order defect: see local-order): " + floors + "; " +
            (kept.holds ? std::string("the floor did not fall")
                        : "from h = " + kept.from_h + " down the defect follows order " +
                              format_scalar(kept.leak_order, 3) + " instead of " + std::to_string(r)) +
            ", a term of size " + power_of_ten(-leak_bits(kept, fine) * std::log10(2.0)) + "·h^" + std::to_string(k) +
            " (about " + format_scalar(leak_bits(kept, fine), 3) + " bits), which is no narrower format's rounding (float 24, double 53, long double 64, float128 113 "
            "bits, within 8): a lower-order term of " + method_words(context) + " itself, which local-order judges";
      } else {
        // The leak's size: δ = ρ/h^k at the smallest judged h, k the order the defect fell to
        // (0 for a floor that did not fall at all).
        const int k = kept.holds ? 0 : std::max(0, static_cast<int>(std::lround(kept.leak_order)));
        const double log10_delta = kept.holds ? fine.log10_floor : kept.log10_defect - k * kept.log10_h;
        const double bits = -log10_delta / std::log10(2.0);
        claim.evidence["leak_order"] = k;
        claim.evidence["leak_size"] = power_of_ten(log10_delta);
        claim.evidence["leak_bits"] = format_scalar(bits, 4);
        const Format format = *format_of(bits);
        claim.evidence["leak_format"] = format.name;
        claim.verdict = "fail";
        claim.explanation =
            "precision leak: " + floors + "; " +
            (kept.holds ? std::string("the floor did not fall")
                        : "from h = " + kept.from_h + " down the defect follows order " + format_scalar(kept.leak_order, 3) +
                              " instead of " + std::to_string(r)) +
            ": a term of size " + power_of_ten(log10_delta) + "·h^" + std::to_string(k) +
            " that more digits do not remove, as if some quantity in " + method_words(context) +
            " carried only about " + format_scalar(bits, 3) + " bits, the rounding of a " + format.name + " (" +
            std::to_string(format.bits) + " bits) — or an error of that size in the method itself, whose "
            "order local-order judges";
      }
    }
  }

 private:
  struct Profile {
    Series series;
    std::vector<double> log10_h, log10_defect;  // the grid and ρ on it (−inf where ρ = 0)
    std::string floor;      // min ρ, 4 digits
    double log10_floor = 0;
  };

  // 10^x written as "m.mme-N", for x beyond the range of a double's exponent too.
  static std::string power_of_ten(double x) {
    const double exponent = std::floor(x);
    return format_scalar(std::pow(10.0, x - exponent), 3) + "e" + std::to_string(static_cast<long>(exponent));
  }

  struct OrderKept {
    bool holds = true;
    std::vector<std::string> orders;  // pairwise orders above a thousand times the floor
    double leak_order = 0;            // where it fails: the median pairwise order from there on
    double log10_h = 0, log10_defect = 0;  // the smallest judged h and ρ there
    std::string from_h;                    // the first h whose pairwise order falls short
  };

  // −log2 δ of the lower-order term δ·h^k a failing profile shows (k = 0 for a floor that did not fall).
  static double leak_bits(const OrderKept& kept, const Profile& fine) {
    const int k = kept.holds ? 0 : std::max(0, static_cast<int>(std::lround(kept.leak_order)));
    const double log10_delta = kept.holds ? fine.log10_floor : kept.log10_defect - k * kept.log10_h;
    return -log10_delta / std::log10(2.0);
  }

  // The narrower format whose unit roundoff a term of `bits` bits matches, within 2^8.
  static std::optional<Format> format_of(double bits) {
    for (const Format& format : narrower_formats)
      if (std::fabs(bits - format.bits) <= format_window_bits) return format;
    return std::nullopt;
  }

  // The case's method in its own words: a program's map has no L_d.
  template <LagrangianSystem System>
  static std::string method_words(const CaseContext<System>& context) {
    if (context.map)
      return context.spec.discretization.kind == "process" ? "the program's map" : "the map " + context.map->name();
    return context.tq ? "the TQ evolution" : "the DEL of L_d";
  }


  // The pairwise orders of `fine` on its large-h side down to a thousand times its floor, each
  // against r − tolerance.
  static OrderKept order_kept(const Profile& fine, int r, double tolerance) {
    OrderKept kept;
    const double threshold = fine.log10_floor + 3;
    std::vector<double> orders;
    std::size_t first_short = 0;
    int short_orders = 0;
    std::string first_short_h;
    for (std::size_t k = 0; k + 1 < fine.log10_h.size(); ++k) {
      if (!(fine.log10_defect[k] >= threshold && fine.log10_defect[k + 1] >= threshold)) break;
      const double order =
          (fine.log10_defect[k] - fine.log10_defect[k + 1]) / (fine.log10_h[k] - fine.log10_h[k + 1]);
      orders.push_back(order);
      kept.orders.push_back(format_scalar(order, 4));
      kept.log10_h = fine.log10_h[k + 1], kept.log10_defect = fine.log10_defect[k + 1];
      if (order < r - tolerance && short_orders++ == 0)
        first_short = orders.size() - 1, first_short_h = power_of_ten(fine.log10_h[k]);
    }
    // A leak needs two pairwise orders short of r above the floor: one is a point in the
    // transition to rounding (a correct decimal program's once read as "about 68.7 bits").
    kept.holds = short_orders < 2;
    if (!kept.holds) kept.from_h = first_short_h;
    if (!kept.holds) {
      std::vector<double> tail(orders.begin() + first_short, orders.end());
      std::nth_element(tail.begin(), tail.begin() + tail.size() / 2, tail.end());
      kept.leak_order = tail[tail.size() / 2];
    }
    return kept;
  }

  // Points of the grid h_k = h_min·10^(−k/points_per_decade), k = 0 … K − 1: from the case's
  // smallest step to margin_decades past where rounding at `finer_digits` digits meets a
  // truncation error of order r, h ≈ 10^(−finer_digits/(r+1)).
  template <LagrangianSystem System>
  static int grid_points(const CaseContext<System>& context, int finer_digits, int r) {
    using std::log10;
    const double h_min = static_cast<double>(log10(context.steps().back()));
    const double decades = h_min + double(finer_digits) / (r + 1) + margin_decades;
    return 1 + static_cast<int>(std::ceil(std::max(0.0, decades) * points_per_decade));
  }

  // ρ(h) on the grid in the context's precision, and its floor: the smallest max of two
  // neighbouring defects (a single defect that cancels to 0 is luck, not a floor), at least ε.
  template <LagrangianSystem System>
  static Profile profile(const CaseContext<System>& context, int points, int digits) {
    using T = typename System::Scalar;
    using std::log10;
    using std::max;
    using std::min;
    using std::pow;
    const T h_min = context.steps().back();
    Profile result;
    Series& series = result.series;
    series.label = "|Φ_h(x0) − F_h(x0)| / |F_h(x0) − x0| at " + std::to_string(digits) + " digits";
    T floor = -1, previous = 0;
    for (int k = 0; k < points; ++k) {
      const T h = h_min * pow(T(10), T(-k) / points_per_decade);
      context.report("precision-leak: local defect at " + std::to_string(digits) + " digits, h = " + format_scalar(h, 4));
      const auto [defect, rounding_level] = relative_local_defect(context, h);
      require_finite(defect, "the local defect at " + std::to_string(digits) + " digits, h = " + format_scalar(h, 4));
      // An exact zero or a point below one rounding of the answer is luck (a program's rounded
      // answer equal to vivv's rounded F_h), not a floor: it counts at the rounding level.
      const T counted = nan_max(defect, rounding_level);
      if (k > 0) floor = floor < 0 ? nan_max(previous, counted) : nan_min(floor, nan_max(previous, counted));
      previous = counted;
      series.h.push_back(to_decimal<T>(h));
      series.error.push_back(to_decimal<T>(defect));
      result.log10_h.push_back(static_cast<double>(log10(h)));
      result.log10_defect.push_back(defect > 0 ? static_cast<double>(log10(defect))
                                               : -std::numeric_limits<double>::infinity());
    }
    floor = nan_max(floor, epsilon<T>());
    series.floor = to_decimal<T>(floor);
    result.floor = format_scalar(floor, 4);
    result.log10_floor = static_cast<double>(log10(floor));
    return result;
  }

  // One step of the case's method from the exact initial state, against the reference, on
  // (q, p): a map steps (q, w); a TQ discretization solves for ṽ; a DEL solves
  // p_begin(q0, q1) = p0 and takes p1 = p_end(q0, q1).
  template <LagrangianSystem System>
  static std::pair<typename System::Scalar, typename System::Scalar> relative_local_defect(
      const CaseContext<System>& context, const typename System::Scalar& h) {
    using T = typename System::Scalar;
    constexpr int N = System::dimension;
    using std::max;
    const auto& system = context.system;
    const State<T, N>& x0 = context.initial;
    const State<T, N> exact = context.exact(h);
    Vector<T, N> q1, p1;
    if (context.map) {
      const State<T, N> x1 = context.map_at(T(0)).step(x0, h);
      q1 = x1.q, p1 = momentum(context.at(h), x1.q, x1.w);
    } else if (context.tq) {
      const auto step = tq_step(system, *context.tq, x0, h);
      require_converged(step.report, "precision-leak: TQ step with h = " + to_decimal<T>(h, 17));
      q1 = step.next.q, p1 = momentum(system, step.next.q, step.next.w);
    } else {
      q1 = start_from_momentum(system, context.scheme.future, x0.q, x0.w, h);
      p1 = p_end(system, context.scheme.future, x0.q, q1, h);
    }
    const Vector<T, N> p0 = momentum(system, x0.q, x0.w), p_exact = momentum(context.at(h), exact.q, exact.w);
    const T error = nan_max(max_norm<T, N>(q1 - exact.q), max_norm<T, N>(p1 - p_exact));
    const T motion = nan_max(max_norm<T, N>(exact.q - x0.q), max_norm<T, N>(p_exact - p0));
    // One rounding of the answer, relative to the motion: ε·max(|q1|, |p1|)/motion.
    const T size = nan_max(max_norm<T, N>(q1), max_norm<T, N>(p1));
    return {error / motion, epsilon<T>() * size / motion};
  }
};

}  // namespace vivv
