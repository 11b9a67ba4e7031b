// symplecticity of a one-step map above the dense limit (core/structure/dense_limit.hpp), where
// the map is known only through products J·v (OneStepMap::jacobian_along: a program's differences
// along v, a few requests each, where its dense J takes requests for each of the 2n coordinates
// and JᵀΩJ costs 16 n³ in the working precision). A map has no generating form vivv can read, so
// each step is judged by its own probes:
//   at step k, `fresh_pairs` new pairs (ξ, η) of standard Gaussian vectors, |ξᵀ(J_kᵀΩJ_k − Ω)η|
//   per unit |ξ||η| against ulps·u_k·max(1, g_k)², u_k the products' relative rounding
//   (last_jacobian_unit) and g_k the largest |J_k v|/|v| of the step's vectors (the probes' view
//   of |J_k|, the dense check's max(1, |J|));
// and the N-step composition by `carried_pairs` pairs carried through the run, against N·ulps·
// max_k(u_k·g_k²)·max(1, |Φξ|/|ξ|, |Φη|/|η|)², as for a DEL map's probes. The chance of a miss
// (core/structure/symplectic_probes.hpp): a step whose ‖J_kᵀΩJ_k − Ω‖₂ is 10 times its tolerance
// passes its fresh pairs with probability at most 10^−fresh_pairs, a defect present at m steps
// at most 10^−(fresh_pairs·m) — a method that is not symplectic is so at every step —, the
// composition 10^−carried_pairs.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/structure/symplectic_probes.hpp"
#include "harness/claims/claim.hpp"
#include "harness/claims/global_order.hpp"

namespace vivv {

// One h of symplecticity in the per-step evidence: its worst step's defect against its tolerance
// (what the check judges) and its composition's defect against its own tolerance (a condition of
// the row), with the columns the report shows.
template <class T>
void add_symplecticity_row(PerStepCheck<T>& check, const T& h, int steps, int ulps, const T& worst_defect,
                           const T& worst_tolerance, const T& largest_defect, const T& composite_defect,
                           const T& composite_tolerance, const T& step_size_factor) {
  check.add(h, worst_defect, worst_tolerance,
            {{"N", steps},
             {"largest_step_defect", to_decimal<T>(largest_defect)},
             {"composite_defect", to_decimal<T>(composite_defect)},
             {"composite_tolerance", to_decimal<T>(composite_tolerance)},
             {"rounding_units", format_scalar(T(worst_defect / (worst_tolerance / ulps)), 3)},
             {"step_size_factor", format_scalar(step_size_factor, 3)}},
            composite_defect <= composite_tolerance);
}

// The pairs judge each step (fresh) and the composition (carried). mutate-rules' 2 -> 3 for the fresh
// pairs survives, as it must: a third pair only lowers the stated miss probability (10^-pairs for a
// step's defect 10 times its tolerance) and changes no verdict a test can pin.
inline constexpr int map_probe_fresh_pairs = 2;
inline constexpr int map_probe_carried_pairs = 2;

// The N-step composition judged by its carried probe pairs (`probe(i)`, i < pairs): each pair's
// |ξᵀ(JᵀΩJ − Ω)η| / (|ξ||η|) against N·ulps·step_unit·max(1, stretch)² (step_unit the largest step's
// rounding unit); the (defect, tolerance) of the pair nearest its tolerance. Shared by a DEL map's
// probes and a one-step map's (symplecticity.hpp).
template <class T, class Probe>
std::pair<T, T> composite_probes(int pairs, int steps, int ulps, const T& step_unit, const T& h, Probe&& probe) {
  T composite_defect = 0, composite_tolerance = 0, composite_ratio = -1;
  for (int i = 0; i < pairs; ++i) {
    const ProbeDefect<T> measured = probe(i);
    const T stretch = nan_max(T(1), measured.stretch);
    const T defect = measured.defect / measured.norms, tolerance = T(steps) * ulps * step_unit * stretch * stretch;
    const std::string composite = "at h = " + format_scalar(h, 6) + " the " + std::to_string(steps) +
                                  "-step composition's ";
    require_finite(defect, composite + "|ξᵀ(JᵀΩJ − Ω)η| / (|ξ||η|)");
    require_finite(tolerance, composite + "tolerance");
    if (defect / tolerance > composite_ratio)
      composite_ratio = defect / tolerance, composite_defect = defect, composite_tolerance = tolerance;
  }
  return {composite_defect, composite_tolerance};
}

// `Claim` is SymplecticityClaim (its ulps, probe_seed, phase_size and Jacobian check rows).
template <class Claim, LagrangianSystem System, class T = typename System::Scalar>
void measure_map_by_probes(const CaseContext<System>& context, const std::vector<int>& exponents,
                           PerStepCheck<T>& check, std::vector<T>& units,
                           std::vector<typename Claim::JacobianCheck>& jacobian_checks, bool& noise_raised) {
  using V = Vector<T, any_size>;
  const int n = context.n;
  const OneStepMap<T, any_size>& map = *context.map;
  // J̃ = S J S⁻¹ with S = diag(2^e, 2^−e) (balanced, core/structure/symplectic.hpp).
  auto rescale = [&](const V& v, int sign) { return balanced_vector<T, any_size>(v, exponents, sign); };
  // J̃ applied to balanced vectors, through the map's products.
  auto apply = [&](const State<T, any_size>& at, const T& h, const std::vector<V>& balanced) {
    std::vector<V> plain;
    for (const V& v : balanced) plain.push_back(rescale(v, -1));
    std::vector<V> images = map.jacobian_along(at, h, plain);
    for (V& image : images) image = rescale(image, 1);
    return images;
  };
  std::size_t index = 0;
  visit_map_trajectories(context, "symplecticity: probes of the map's Jacobians", [&](const T& h, const auto& x) {
    GaussianProbes draw(Claim::probe_seed + index++);
    const int steps = static_cast<int>(x.size()) - 1;
    std::vector<V> start, carried;  // ξ_1, η_1, ξ_2, η_2, …: at step 0, and carried
    for (int i = 0; i < 2 * map_probe_carried_pairs; ++i) start.push_back(draw.next<T>(2 * n));
    carried = start;
    V scale = V::Zero(2 * n);
    struct Probed {
      T defect, unit, stretch;  // max over the fresh pairs of |ξᵀDη|/(|ξ||η|); u_k; g_k
    };
    std::vector<Probed> probed;
    for (int k = 0; k < steps; ++k) {
      scale = scale.cwiseMax(V(Claim::template phase_size<T, any_size>(context, context.at_step(h, k), x[k].q, x[k].w,
                                                                         static_cast<std::size_t>(k), x.size() - 1)));
      std::vector<V> vectors;
      for (int i = 0; i < 2 * map_probe_fresh_pairs; ++i) vectors.push_back(draw.next<T>(2 * n));
      vectors.insert(vectors.end(), carried.begin(), carried.end());
      context.map_at(T(k * h));  // the map's clock at x_k's time (an L that depends on time)
      const std::vector<V> images = apply(x[k], h, vectors);
      Probed step{0, map.last_jacobian_unit(), 1};
      for (std::size_t v = 0; v < vectors.size(); ++v)
        step.stretch = nan_max(step.stretch, T(images[v].norm() / vectors[v].norm()));
      for (int i = 0; i < map_probe_fresh_pairs; ++i) {
        const ProbeDefect<T> probe = probe_defect<T>(vectors[2 * i], vectors[2 * i + 1], images[2 * i], images[2 * i + 1]);
        step.defect = nan_max(step.defect, T(probe.defect / probe.norms));
      }
      require_finite(step.defect, "at h = " + format_scalar(h, 6) + ", step " + std::to_string(k) + " of " +
                                      std::to_string(steps) + " |ξᵀ(JᵀΩJ − Ω)η| / (|ξ||η|)");
      for (std::size_t i = 0; i < carried.size(); ++i) carried[i] = images[2 * map_probe_fresh_pairs + i];
      probed.push_back(step);
    }
    // A program's answer noise is measured at the first step and every eighth, the largest so far
    // standing for the steps between; the run's last unit (the largest) stands for every step, as
    // the dense check has it, scaled by each step's g as the map scales it.
    if (!probed.empty() && probed.back().unit > map.jacobian_unit()) {
      const Probed last = probed.back();
      for (Probed& step : probed)
        step.unit = nan_max(step.unit, T(last.unit * last.stretch / step.stretch));
    }
    T worst_ratio = -1, worst_defect = 0, worst_tolerance = 0, largest_defect = 0, step_unit = 0, worst_unit = 0;
    std::size_t worst = 0;
    for (std::size_t k = 0; k < probed.size(); ++k) {
      const Probed& step = probed[k];
      noise_raised = noise_raised || step.unit > map.jacobian_unit();
      const T tolerance = Claim::ulps * step.unit * step.stretch * step.stretch;
      const std::string where = "at h = " + format_scalar(h, 6) + ", step " + std::to_string(k) + " of " +
                                std::to_string(steps) + " (the probes' largest stretch " +
                                format_scalar(step.stretch, 3) + ")";
      require_finite(tolerance, where + " its tolerance");
      // An allowance of |Ω| = 1 or more would pass JᵀΩJ = 0 (the dense check's rule).
      if (!(tolerance < 1))
        throw UnmeasurableJacobian(where + ": its rounding allowance " + format_scalar(tolerance, 3) +
                                   " reaches |Ω| = 1, so even JᵀΩJ = 0 would pass: a Jacobian this large "
                                   "leaves the identity unmeasurable in this precision");
      step_unit = nan_max(step_unit, T(step.unit * step.stretch * step.stretch));
      largest_defect = nan_max(largest_defect, step.defect);
      if (step.defect / tolerance > worst_ratio)
        worst_ratio = step.defect / tolerance, worst_defect = step.defect, worst_tolerance = tolerance, worst = k,
        worst_unit = step.unit;
    }
    const auto [composite_defect, composite_tolerance] = composite_probes<T>(
        map_probe_carried_pairs, steps, Claim::ulps, step_unit, h,
        [&](int i) { return probe_defect<T>(start[2 * i], start[2 * i + 1], carried[2 * i], carried[2 * i + 1]); });
    add_symplecticity_row<T>(check, h, steps, Claim::ulps, worst_defect, worst_tolerance, largest_defect,
                             composite_defect, composite_tolerance, T(worst_unit / map.jacobian_unit()));
    units.push_back(worst_tolerance / Claim::ulps);
    // The judged step's products against differences of the map on (q, p) along two directions:
    // w from p by the inverse Legendre transform, one step, p' = FL(q', w').
    // (For an L that depends on time, p at the step's start is FL at t0 + worst·h, p' at h later;
    // the map's clock stays at the step's start for every call below.)
    const State<T, any_size>& at = x[worst];
    const System before = context.at_step(h, static_cast<long>(worst)),
                 after = context.at_step(h, static_cast<long>(worst) + 1);
    context.map_at(T(worst * h));
    auto step = [&](const V& y) {
      State<T, any_size> from;
      from.q = y.head(n);
      from.w = velocity_for_momentum(before, from.q, V(y.tail(n)), at.w);
      const State<T, any_size> to = map.step(from, h);
      V out(2 * n);
      out << to.q, momentum(after, to.q, to.w);
      return out;
    };
    auto product = [&](const V& v) { return map.jacobian_along(at, h, {v}).front(); };
    V y(2 * n);
    y << at.q, momentum(before, at.q, at.w);
    std::optional<V> rounding;  // a double program's answers' measured noise, as the dense check has it
    if (const std::optional<T> noise_r = map.answer_noise(at, h)) {
      rounding = V(2 * n);
      rounding->setConstant(T(3 * *noise_r));
    }
    const JacobianAgreement<T> agreement = compare_directions_with_differences<T>(
        step, product, y, scale, draw, 2, context.working_epsilon(), rounding ? &*rounding : nullptr);
    jacobian_checks.push_back(Claim::jacobian_check_row(h, worst, agreement));
  });
}

}  // namespace vivv
