// A case's one-step map computed by another program (discretization kind "process", protocol
// vivv-map/1, harness/process/program.hpp): the OneStepMap the map claims check (global-order,
// symplecticity, energy-behaviour, discrete-noether, precision-leak).
//
// The program works on (q, p), p = ∂L/∂w; vivv's states are (q, w), so a step sends
// (h, q, p = FL(q, w)) and takes w' from the answer's p' by the inverse Legendre transform.
// Numbers travel as decimal strings with at least D significant digits, D the digits that
// carry the working precision (17 for a double); an answer with fewer is refused, since a
// program that computes in double and prints 40 digits would pass the digits on as noise.
//
// The Jacobian ∂(q', p')/∂(q, p) that symplecticity measures comes from central differences of
// a second instance of the program, started at D₂ = 2D + 10 digits: with the step
// δ = 10^(−⌈D₂/3⌉)·max(1, |y_j|), the difference's truncation (δ²) and rounding (10^−D₂/δ) are
// both about 10^(−2D₂/3) = 10^(−(4D + 20)/3), far below the working precision's 10^−D, so
// JᵀΩJ − Ω measures the map and not the differences. That holds only if the program really
// computes with D₂ digits: the first Jacobian and every eighth are computed again at ten times
// the width, and a change beyond ε·|J| is UnmeasurableJacobian naming the program (padded
// digits): symplecticity errs, the other claims are judged.
//
// An answer beyond 10^divergence_digits times the reference orbit's size is a divergence
// (MapDiverged), thrown before vivv computes with it: each claim that ran the map at that h is
// inconclusive (harness/claims/claim.hpp).
#pragma once

#include <algorithm>
#include <chrono>
#include <iomanip>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

#include "core/structure/energy.hpp"
#include "core/maps/one_step_map.hpp"
#include "core/platform/text.hpp"
#include "harness/process/answer_fields.hpp"
#include "harness/process/program.hpp"

namespace vivv {

template <LagrangianSystem System>
class ProcessMap final : public OneStepMap<typename System::Scalar, System::dimension> {
  using T = typename System::Scalar;
  static constexpr int N = System::dimension;

 public:
  // `system_json`: the system as the case file gives it, every parameter filled in;
  // `orbit_size`: the reference orbit's size, max |q_i|, |p_i| over its states vivv knows.
  // `double_program`: the case's discretization.precision "double" — the program computes in
  // IEEE double, so its Jacobian comes from differences of its own steps at a double's widths.
  ProcessMap(System system, MapProcess::Options options, nlohmann::json system_json, int order,
             const T& orbit_size, bool double_program = false)
      : system_(std::move(system)),
        n(dimension_of(system_)),
        options_(std::move(options)),
        system_json_(std::move(system_json)),
        order_(order),
        double_program_(double_program),
        digits_(double_program ? std::numeric_limits<double>::max_digits10 : round_trip_digits<T>()),
        orbit_size_(orbit_size),
        bound_(to_decimal<T>(scale_bound(orbit_size))),
        timed_(depends_on_time(system_)),
        time_(system_time(system_)),
        process_(start(digits_)) {}

  // For an L that depends on time: the time of the states the next requests start from, sent as
  // their "t" (docs/process-protocol.md), and the time at which vivv converts between w and p — the
  // request's p = FL(t, q, w), the answer's w from its p at t + h. Any other L ignores it.
  void set_time(const T& t) const override {
    if (!timed_) return;
    time_ = t;
    const std::string text = to_decimal<T>(t);
    process_->set_time(text);
    if (fine_) fine_->set_time(text);
  }

  // The orbit's size once more of it is known (the reference's state at T: the program is greeted
  // before the reference flow runs, so that one that declines or fails says so in seconds).
  void widen_orbit(const T& size) {
    using std::max;
    orbit_size_ = max(orbit_size_, size);
    bound_ = to_decimal<T>(scale_bound(orbit_size_));
  }

  // How far beyond the orbit's size an answer may lie before its run counts as diverged: 10^10.
  // A method that errs by the orbit's size itself (order 0) stays 10 orders of magnitude below
  // it; an answer beyond it is not followed, since vivv's work on a state — the inverse Legendre
  // transform's Newton, cos(q) — can take minutes at |q| = 10^300000000.
  static constexpr int divergence_digits = 10;

  std::string name() const override { return process_->name(); }
  int order() const override { return order_; }
  std::string jacobian_method() const override {
    if (process_->uses_extension(jacobian_extension))
      return "the program's own Jacobian (extension \"jacobian\"), sent with its answer at " +
             std::to_string(digits_) + " digits; the first of each h and every " +
             std::to_string(recheck) + "th checked against central differences of its steps at width 10^-" +
             std::to_string(coarse_exponent()) + " and 10^-" + std::to_string(coarse_exponent() - 1);
    if (double_program_)
      return "central differences of one step of " + name() +
             " (precision \"double\": the same instance, 17 digits) at widths δ = 10^-" +
             std::to_string(double_exponent()) +
             "·max(1, |y_j|) and 2δ in each of (q, p), extrapolated: (4·J_δ − J_2δ)/3; its rounding "
             "from the noise r of the program's answers, measured by fourth differences at spacings 10^-" +
             std::to_string(digits_ / 2) + " and 10^-" + std::to_string(double_exponent() + 2) + " (at least 1.5·r/δ)";
    return "central differences of one step of " + name() + " in a second instance of it at " +
           std::to_string(fine_digits()) + " digits, step 10^-" +
           std::to_string(difference_exponent()) + "·max(1, |y_j|) in each of (q, p)";
  }
  // A double program's Jacobian by extrapolated differences at width δ = 10^-e: its rounding,
  // 10^(e + 2 − D) (10^-11 at D = 17, e = 4): (4·r/δ + r/2δ)/3 ≈ 1.5·r/δ for a program whose
  // answers err by r, a few ulps of |Φ| (≈ 5·10^-16 · |Φ|/max(1, |y|)), and JᵀΩJ multiplies two
  // such. Calibrated on correct NumPy maps (Störmer–Verlet on the pendulum, implicit midpoint on
  // Hénon–Heiles, Yoshida's composition on Kepler): at most 0.55 of it, where 10^-12 measured up
  // to 5.4. Any other Jacobian is exact to the digits it carries.
  T jacobian_unit() const override {
    using std::pow;
    if (double_program_ && !process_->uses_extension(jacobian_extension))
      return T(pow(T(10), double_exponent() + 2 - digits_));
    return double_program_ ? T(std::numeric_limits<double>::epsilon()) : epsilon<T>();
  }
  // A double program's answers may carry more rounding than a few ulps: an implicit solver that
  // stops at 1e-15 relative in q' and forms p' from (q' − q)/h passes its last digits on to p'
  // times 1/h, so the noise grows as h falls (a spherical pendulum's midpoint DEL in Python floats
  // measured 3.1e-11 … 2.2e-10 at h = 1/8 … 1/64 against a fixed 1.6e-10). The noise r is
  // measured, not assumed: fourth differences of the answers at spacings s = 10^-⌊D/2⌋·max(1, |y_j|)
  // and 10^-6·max(1, |y_j|) along four directions, |Δ⁴| / √70 (the spread of Δ⁴ of independent
  // rounding errors of spread r; its truncation, s⁴ times the map's fourth derivative, is at most
  // 10^-24 of that derivative), the largest over the answers' entries and spacings (noise_near).
  // The Jacobian's unit is then at least 1.5·r·10^e / max(1, |J|).
  T last_jacobian_unit() const override { return last_unit_; }
  // The same measurement of a double program's noise at x for local-order's floor (the last one
  // kept: the floor is asked for at the same state and h more than once).
  std::optional<T> answer_noise(const State<T, N>& x, const T& h) const override {
    if (!double_program_) return std::nullopt;
    const std::vector<std::string> y = point(x);
    std::string key = to_decimal<T>(h);
    for (const std::string& v : y) key += " " + v;
    if (timed_) key += " t " + to_decimal<T>(time_);
    if (noise_key_ != key) {
      PrecisionGuard guard(digits_ + 30);
      noise_ = from_decimal<T>(to_decimal<R>(noise_near(key.substr(0, key.find(' ')), y, h)));
      noise_key_ = key;
    }
    return noise_;
  }

  std::optional<double> answer_noise_in_ulps() const override {
    if (!double_program_ || noise_in_ulps_ < 0) return std::nullopt;
    return noise_in_ulps_;
  }

  State<T, N> step(const State<T, N>& x, const T& h) const override {
    const nlohmann::json answer = process_->request(state_request(x, h));
    const std::vector<T> y = answer_state<T>(*process_, answer, digits_, h);
    State<T, N> next{Vector<T, N>(n), Vector<T, N>(n)};
    Vector<T, N> p_next(n);
    for (int i = 0; i < n; ++i) next.q[i] = y[i], p_next[i] = y[n + i];
    next.w = at_system_time(T(time_ + h), [&](const System& at) { return velocity_for_momentum(at, next.q, p_next, x.w); });
    last_ = {next, p_next};
    count_evaluations(answer);
    return next;
  }

  // Φ_h^count(x) in few requests {"h", "q", "p", "steps": k}, for a program that took up the
  // extension "steps": the program takes the k steps itself and answers the last state with
  // "steps": m, the steps it took — k, or fewer where a state on the way left the finite numbers
  // (it then answers the state before). The first request asks for 16 steps, each next one for as
  // many as take about a second at the last one's pace (at most 16 times as many, a tenth of
  // --process-timeout at most), so that no answer comes near the timeout however long the run.
  // nullopt for m < k, and for an answer beyond the problem's scale or whose w Newton does not
  // find from the run's start: the run is then taken one request a step, which finds and names
  // the step.
  std::optional<State<T, N>> steps(const State<T, N>& x, const T& h, long count) const override;

  // x_1 … x_count in few requests {"h", "q", "p", "steps": k, "trajectory": true}, for a program
  // that took up "steps" and "trajectory": each answer carries, beside the last state, every state
  // its k steps reached ("trajectory": k arrays of 2n decimal strings, q then p), paced as steps();
  // nullopt where steps() would give none, and the run is then taken one request a step.
  std::optional<std::vector<State<T, N>>> trajectory(const State<T, N>& x, const T& h, long count) const override;

  std::optional<long> reported_evaluations() const override {
    if (!process_->uses_extension(evaluations_extension)) return std::nullopt;
    return evaluations_;
  }

  Matrix<T, twice(N), twice(N)> jacobian(const State<T, N>& x, const T& h) const override {
    const long step_index = next_jacobian_step(h);
    const std::vector<std::string> y = point(x);
    const std::string step = to_decimal<T>(h);
    last_unit_ = jacobian_unit();
    if (process_->uses_extension(jacobian_extension)) return own_jacobian(y, h, step_index);
    Columns columns;  // ∂(q', p')/∂y_j, as decimals
    if (double_program_) {
      using std::abs, std::pow;
      // One instance at 17 digits, Richardson's extrapolation of central differences at widths δ
      // and 2δ, (4·J_δ − J_2δ)/3: its truncation is O(δ⁴), so that δ = 10^-4 keeps it below the
      // rounding, about 1.5·r/δ (r the program's own rounding) — where one width would leave δ²·Φ‴ in the
      // measurement (up to 10 of its units on Kepler near pericentre at δ = 10^-5).
      PrecisionGuard guard(digits_ + 30);
      const auto narrow = differences(*process_, digits_, step, y, double_exponent(), h);
      const auto wide = differences(*process_, digits_, step, y, double_exponent(), h, 2);
      Differences extrapolated(2 * n, std::vector<R>(2 * n));
      R largest = 1;
      for (int j = 0; j < 2 * n; ++j)
        for (int i = 0; i < 2 * n; ++i)
          extrapolated[j][i] = (4 * narrow[j][i] - wide[j][i]) / 3,
          largest = std::max(largest, R(abs(extrapolated[j][i])));
      columns = decimals(extrapolated);
      // The noise of the answers, measured at the first Jacobian of each h and every
      // `recheck`-th; the largest so far at this h stands for the steps between.
      if (step_index % recheck == 0) answer_noise_ = std::max(answer_noise_, noise_near(step, y, h));
      // Extrapolated differences carry about 1.5·r/δ of it, δ ≥ 10^-e: relative to |J|.
      last_unit_ = std::max(jacobian_unit(),
                            from_decimal<T>(to_decimal<R>(R(3 * answer_noise_ * pow(R(10), double_exponent()) /
                                                            (2 * largest)))));
    } else {
      columns = fine_differences(y, step, h);
    }
    Matrix<T, twice(N), twice(N)> jacobian(2 * n, 2 * n);
    for (int i = 0; i < 2 * n; ++i)
      for (int j = 0; j < 2 * n; ++j) jacobian(i, j) = from_decimal<T>(columns[j][i]);
    return jacobian;
  }

  // J·v for each direction without J where the program does not send it: differences along v,
  // as jacobian() takes them along each coordinate — a double program's extrapolated pair of widths
  // (4 requests a direction, where J takes 8n), the second instance's one width (2, where J takes
  // 4n) —, the answer noise measured as for J. The unit (last_jacobian_unit) is relative to
  // max(1, the largest |J·v|/|v|): entry i of J·v errs by about 1.5·r·10^e·max_j |v_j| / max(1,
  // |y_j|) (a double program's answers erring by r), what a column's entries err by times |v|'s
  // largest entry. A program that sends its J: that J times each v.
  std::vector<Vector<T, twice(N)>> jacobian_along(const State<T, N>& x, const T& h,
                                                  const std::vector<Vector<T, twice(N)>>& directions) const override {
    using V = Vector<T, twice(N)>;
    if (process_->uses_extension(jacobian_extension)) {
      const Matrix<T, twice(N), twice(N)> j = jacobian(x, h);
      std::vector<V> out;
      for (const V& v : directions) out.push_back(j * v);
      return out;
    }
    const long step_index = next_jacobian_step(h);
    const std::vector<std::string> y = point(x);
    const std::string step = to_decimal<T>(h);
    last_unit_ = jacobian_unit();
    std::string unit;  // a double program's measured unit, a decimal
    const int count = static_cast<int>(directions.size());
    // Decimals in and out, so that no T is made or read at the guard's precision (an MPFR T would
    // take it: the working precision's ε must stay the working one's).
    std::vector<std::vector<std::string>> given(static_cast<std::size_t>(count), std::vector<std::string>(2 * n));
    for (int k = 0; k < count; ++k)
      for (int i = 0; i < 2 * n; ++i) given[k][i] = to_decimal<T>(directions[k][i]);
    const std::string epsilon_of_T = to_decimal<T>(epsilon<T>());
    Columns products;
    {
      PrecisionGuard guard(double_program_ ? digits_ + 30 : fine_digits() + 10);
      const auto direction = [&](int k) {
        std::vector<R> u(2 * n);
        for (int i = 0; i < 2 * n; ++i) u[i] = from_decimal<R>(given[k][i]);
        return u;
      };
      if (double_program_) {
        using std::pow, std::sqrt;
        const auto narrow = along(*process_, digits_, step, y, count, direction, double_exponent(), h);
        const auto wide = along(*process_, digits_, step, y, count, direction, double_exponent(), h, 2);
        Differences extrapolated(count, std::vector<R>(2 * n));
        R largest = 1;
        for (int k = 0; k < count; ++k) {
          R image = 0, length = 0;
          for (int i = 0; i < 2 * n; ++i) {
            extrapolated[k][i] = (4 * narrow[k][i] - wide[k][i]) / 3;
            image += extrapolated[k][i] * extrapolated[k][i];
            const R v = from_decimal<R>(given[k][i]);
            length += v * v;
          }
          if (length > 0) largest = std::max(largest, R(sqrt(R(image / length))));
        }
        products = decimals(extrapolated);
        if (step_index % recheck == 0) answer_noise_ = std::max(answer_noise_, noise_near(step, y, h));
        unit = to_decimal<R>(R(3 * answer_noise_ * pow(R(10), double_exponent()) / (2 * largest)));
      } else {
        products = decimals(fine_along(y, step, h, count, direction, epsilon_of_T));
      }
    }
    if (!unit.empty()) last_unit_ = std::max(jacobian_unit(), from_decimal<T>(unit));
    std::vector<V> out(static_cast<std::size_t>(count), V(2 * n));
    for (int k = 0; k < count; ++k)
      for (int i = 0; i < 2 * n; ++i) out[k][i] = from_decimal<T>(products[k][i]);
    return out;
  }

  // The extension a program takes up to send its own Jacobian with each answer.
  static constexpr const char* jacobian_extension = "jacobian";
  // The extension a program takes up to say, in each step's answer, how many evaluations (of its
  // forces, or of L) the step made: "evaluations": a whole number, 0 or more.
  static constexpr const char* evaluations_extension = "evaluations";
  // The extension a program takes up to take several steps in one request ("steps": k), answering
  // only the last state.
  static constexpr const char* steps_extension = "steps";
  // The extension a program that took up "steps" takes up to answer, beside the last state, every
  // state of the k steps ("trajectory": true in the request), for the claims that read them all.
  static constexpr const char* trajectory_extension = "trajectory";

 private:
  using R = mpfr_real;

  // {"h": h, "q": x's q, "p": FL(x)}: a step's request, as decimals of the working precision.
  nlohmann::json state_request(const State<T, N>& x, const T& h) const {
    const Vector<T, N> p = momentum_at(x);
    nlohmann::json request = {{"h", to_decimal<T>(h)}, {"q", nlohmann::json::array()}, {"p", nlohmann::json::array()}};
    for (int i = 0; i < n; ++i) {
      request["q"].push_back(to_decimal<T>(x.q[i]));
      request["p"].push_back(to_decimal<T>(p[i]));
    }
    return request;
  }

  // A program that took up "evaluations" says in each step's answer how many it made: added up.
  void count_evaluations(const nlohmann::json& answer) const {
    if (process_->uses_extension(evaluations_extension))
      evaluations_ += answer_count(*process_, answer, evaluations_extension, 1000000000000L,
                                   "the count of evaluations this step made (a whole number, 0 to 10^12)");
  }

  // `count` steps from x in requests of batch_ steps (and at most `at_most`), each next batch as
  // many as take about a second at the last one's pace (at most 16 times as many, a tenth of
  // --process-timeout at most): `request(from, asked)` takes `asked` steps from `from` and gives
  // their end state, or nullopt, which ends the run with nullopt.
  // For an L that depends on time, each request starts at the time of its first state, t + (steps
  // so far)·h, t the time set before the run (set_time), which is the time again after it.
  template <class Request>
  std::optional<State<T, N>> paced_batches(const State<T, N>& x, const T& h, long count, const Request& request,
                                           long at_most = std::numeric_limits<long>::max()) const;

  // One request for `count` steps from x with every state answered (extensions "steps" and
  // "trajectory"), appended to `states`: the end state, or nullopt as batched_request. The
  // answer's "trajectory" must hold the `count` states, each 2n decimal strings at the greeting's
  // digits, the last of them the answer's "q" and "p"; anything else is a malformed answer.
  std::optional<State<T, N>> batched_states(const State<T, N>& x, const T& h, long count,
                                            std::vector<State<T, N>>& states) const;

  // The answer to one request for `count` steps from x (extension "steps"; with `every`, each
  // state too: "trajectory"), its evaluations counted; nullopt where it took fewer steps.
  std::optional<nlohmann::json> batch_answer(const State<T, N>& x, const T& h, long count, bool every) const;

  // One request for `count` steps from x (extension "steps"): the end state, or nullopt (above).
  std::optional<State<T, N>> batched_request(const State<T, N>& x, const T& h, long count) const;
  using Differences = std::vector<std::vector<R>>;      // [j][i] = ∂y'_i/∂y_j
  using Columns = std::vector<std::vector<std::string>>;  // the same, as decimals

  // Central differences of one step of `process` (answering with `digits` digits) at y and step
  // size `step`, width 10^(−exponent)·max(1, |y_j|), column by column, in MPFR at the caller's
  // PrecisionGuard.
  Differences differences(MapProcess& process, int digits, const std::string& step,
                          const std::vector<std::string>& y, int exponent, const T& h,
                          int multiple = 1) const {
    const auto column = [&](int j) {
      std::vector<R> u(2 * n, R(0));
      u[j] = 1;
      return u;
    };
    return along(process, digits, step, y, 2 * n, column, exponent, h, multiple);
  }

  // J·u for each of `count` directions u = direction(k) by central differences along u, in MPFR at
  // the caller's PrecisionGuard: the point moves by ±δ·s·u, δ = multiple·10^(−exponent), s the
  // scale at which the largest |u_j|·s / max(1, |y_j|) is 1 — for a column j, s = max(1, |y_j|), the
  // coordinate's own width, so a column is what differences() always took. Entries where u_j = 0
  // keep y's decimal. 2 requests a direction.
  template <class Direction>
  Differences along(MapProcess& process, int digits, const std::string& step, const std::vector<std::string>& y,
                    int count, const Direction& direction, int exponent, const T& h, int multiple = 1) const;
  static Columns decimals(const Differences& d) {
    Columns columns(d.size());
    for (std::size_t j = 0; j < d.size(); ++j)
      for (std::size_t i = 0; i < d[j].size(); ++i) columns[j].push_back(to_decimal<R>(d[j][i]));
    return columns;
  }

  // The Jacobian by differences of a second instance at D₂ = 2D + 10 digits; the first and every
  // `recheck`-th are computed again at ten times the width and at a coarse width (padded digits).
  Columns fine_differences(const std::vector<std::string>& y, const std::string& step,
                           const T& h) const {
    const auto column = [&](int j) {
      std::vector<R> u(2 * n, R(0));
      u[j] = 1;
      return u;
    };
    const std::string epsilon_of_T = to_decimal<T>(epsilon<T>());
    PrecisionGuard guard(fine_digits() + 10);
    return decimals(fine_along(y, step, h, 2 * n, column, epsilon_of_T));
  }
  // The same along `count` directions (along): J·u for each, in MPFR at the caller's PrecisionGuard
  // (fine_digits() + 10; `epsilon_of_T` the working precision's ε, taken before it), the first and
  // every `recheck`-th call checked at 10 times the width and at the coarse width as columns are.
  template <class Direction>
  Differences fine_along(const std::vector<std::string>& y, const std::string& step, const T& h, int count,
                         const Direction& direction, const std::string& epsilon_of_T) const;

  // The program's own Jacobian (extension "jacobian") at y: one request marked "jacobian": true,
  // its answer's "jacobian", 2n rows of 2n decimal strings of D digits, row i = ∂y'_i/∂(q, p)
  // (a program may send it with every answer; vivv reads it only where it asked). The first of
  // each h and every `recheck`-th are checked against central differences of the program's own
  // steps at the coarse width 10^-c and at 10^-(c-1): an entry may differ from the first by 4
  // times their difference (the truncation's size, over-estimated) + 100·10^(c-D)·max(1, |J|)
  // (the rounding's); beyond that it is a wrong entry, a finding naming the step and the entry.
  Matrix<T, twice(N), twice(N)> own_jacobian(const std::vector<std::string>& y, const T& h,
                                       long step_index) const;

  // The index of this Jacobian along its h's run: claims ask for them step by step, one h after
  // another.
  long next_jacobian_step(const T& h) const {
    const std::string key = to_decimal<T>(h);
    if (key != jacobian_h_) jacobian_h_ = key, jacobian_step_ = 0, answer_noise_ = 0;
    return jacobian_step_++;
  }

  // The spread r of a double program's answers' rounding near y (last_jacobian_unit, answer_noise): fourth
  // differences at spacing s along four directions — (1, 1, …), (1, −1, …), q alone and p alone —,
  // each point's answer one request (33 a measurement); |Δ⁴ f_i| / √70 for every entry i of
  // (q', p'), the largest. Two spacings: 10^-⌊D/2⌋, and 10^-(e+2) (10^-6), a hundredth of the
  // Jacobian's widths: rounding that is constant over
  // bins wider than the fine spacing — a force rounded to float32, whose bins are 6·10^-8 of it —
  // is smooth between bin edges, and the fine spacing alone measured it at 3·10^4 … 8·10^6 ε from
  // one h to the next, while differences at the widths 10^-4 see it whole (symplecticity failed a
  // Verlet with such a force by 1.5 times its tolerance at the h where the estimate was low). The
  // coarse spacing's truncation, s⁴ times the map's fourth derivative, is 10^-24 of it. Quantized
  // rounding makes Δ⁴ an integer number of bins, often 0: with two directions a Verlet whose force
  // kept 30 bits measured 1500 ε at one state where four find 6·10⁴. In MPFR at
  // the caller's PrecisionGuard.
  R noise_near(const std::string& step, const std::vector<std::string>& y, const T& h) const;

  // UnmeasurableJacobian: the second instance's differences show that it does not compute with
  // the digits it was greeted with; `what` is the evidence. A finding about the program (its
  // symplecticity cannot be judged), not bad input: every other claim is still judged.
  [[noreturn]] void unmeasurable(const std::string& what) const {
    throw UnmeasurableJacobian(
        fine_->answering() + ": " + what + ": it does not compute with the " +
        std::to_string(fine_digits()) + " digits its greeting asked for. Those digits, D2 = 2D + 10 " +
        "for a working precision of D = " + std::to_string(digits_) +
        ", let central differences of one step resolve the Jacobian far below the working "
        "precision (their truncation and rounding both about 10^-(2 D2/3)); a program that "
        "rounds to fewer digits, in one term or throughout, makes the differences measure its "
        "rounding instead, so symplecticity cannot be judged. precision-leak measures how many "
        "digits the program really carries; a program that cannot compute with D2 digits should "
        "decline the greeting");
  }

  int fine_digits() const { return 2 * digits_ + 10; }
  // A double program's difference width 10^-e, e = ⌊(D − 5)/3⌋ (4 at D = 17), extrapolated with
  // 2δ: truncation 10^-16 times the map's fifth derivative, rounding about 10^-11 (jacobian_unit).
  int double_exponent() const { return (digits_ - 5) / 3; }
  int difference_exponent() const { return (fine_digits() + 2) / 3; }
  int coarse_exponent() const { return (digits_ + 2) / 3; }

  // 10^divergence_digits times the orbit's size, or the largest finite T where that overflows
  // (an orbit above about 10^298 in double): the bound must be a number.
  static T scale_bound(const T& orbit_size) {
    using std::isfinite, std::pow;
    const T bound = T(pow(T(10), divergence_digits)) * orbit_size;
    return isfinite(bound) ? bound : std::numeric_limits<T>::max();
  }

  // h in the stream's shortest form with 6 significant digits: "0.125", "4".
  static std::string shortest(const T& h) {
    std::ostringstream out;
    out << std::setprecision(6) << h;
    return out.str();
  }

  // MapDiverged naming the program, the request, the field key[i] and the number when `value`,
  // from `process`'s answer for a step of size h, lies beyond `bound` (scale_bound_in).
  template <class S>
  void require_within_scale(const MapProcess& process, const S& value, const S& bound, const char* key, int i,
                            const T& h) const {
    using std::abs;
    if (abs(value) <= bound) return;
    throw MapDiverged(process.answering() + ": " + key + "[" + std::to_string(i) + "] = " +
                          to_decimal<S>(value, 6) + " lies beyond 10^" +
                          std::to_string(divergence_digits) + " times the reference orbit's size " +
                          to_decimal<T>(orbit_size_, 3) +
                          " (max |q_i|, |p_i| of its states at t = 0 and T)",
                      shortest(h));
  }

  // The answer's (q_1 … q_n, p_1 … p_n) in S, read with `digits` digits (answer_fields.hpp), then
  // each checked within the orbit's scale: what every reading of a state from a program does.
  template <class S>
  std::vector<S> answer_state(const MapProcess& process, const nlohmann::json& answer, int digits, const T& h) const {
    std::vector<S> y(2 * n);
    for (int i = 0; i < n; ++i) {
      y[i] = answer_number<S>(process, answer, "q", i, n, digits);
      y[n + i] = answer_number<S>(process, answer, "p", i, n, digits);
    }
    const S bound = scale_bound_in<S>();
    for (int i = 0; i < n; ++i) {
      require_within_scale(process, y[i], bound, "q", i, h);
      require_within_scale(process, y[n + i], bound, "p", i, h);
    }
    return y;
  }

  // 10^divergence_digits times the orbit's size in S (read once an answer, not once a number);
  // in a double the largest finite one where the bound lies beyond double's range.
  template <class S>
  S scale_bound_in() const {
    try {
      return from_decimal<S>(bound_);
    } catch (const std::out_of_range&) {
      return std::numeric_limits<S>::max();
    }
  }

  // A double program's answer, read as the doubles it carries (its 17 digits read back as the
  // double the program wrote) and widened to R exactly: the same numbers as reading the decimals
  // in R, to 5·10^-17 of each, without R's decimal conversions.
  std::vector<R> double_answer(const MapProcess& process, const nlohmann::json& answer, const T& h) const {
    const std::vector<double> read = answer_state<double>(process, answer, digits_, h);
    return std::vector<R>(read.begin(), read.end());
  }

  // (q, p = FL(q, w)) at x as the decimals a request carries.
  std::vector<std::string> point(const State<T, N>& x) const {
    const Vector<T, N> p = momentum_at(x);
    std::vector<std::string> y(2 * n);
    for (int i = 0; i < n; ++i) y[i] = to_decimal<T>(x.q[i]), y[n + i] = to_decimal<T>(p[i]);
    return y;
  }

  // p = FL(q, w), taken from the program's last answer when x is the state it gave (a run's next
  // step starts there): no evaluation of L, and the p the program wrote rather than its round
  // trip through w.
  Vector<T, N> momentum_at(const State<T, N>& x) const {
    if (last_ && last_->first.q == x.q && last_->first.w == x.w) return last_->second;
    return at_system_time(time_, [&](const System& at) { return momentum(at, x.q, x.w); });
  }

  // f(the system at t): the case's system itself where L does not depend on time (no copy).
  template <class F>
  auto at_system_time(const T& t, const F& f) const {
    if (timed_) return f(at_time(system_, t));
    return f(system_);
  }

  std::unique_ptr<MapProcess> start(int digits) const {
    const nlohmann::json greeting = {{"protocol", map_protocol},
                                     {"digits", digits},
                                     {"dimension", n},
                                     {"system", system_json_},
                                     {"extensions", nlohmann::json::array(
                                          {jacobian_extension, evaluations_extension, steps_extension, trajectory_extension,
                                           pipeline_extension})}};
    auto process = std::make_unique<MapProcess>(options_, greeting);
    if (timed_) process->set_time(to_decimal<T>(time_));  // its requests' "t" from the first on
    return process;
  }

  System system_;
  int n;  // the system's coordinates
  MapProcess::Options options_;
  nlohmann::json system_json_;
  int order_;
  bool double_program_;
  int digits_;
  T orbit_size_;
  std::string bound_;  // 10^divergence_digits times the orbit's size, a decimal
  bool timed_;         // L depends on time: requests carry "t", and FL is taken at their times
  mutable T time_;     // the time of the state the next request starts from (set_time)
  std::unique_ptr<MapProcess> process_;
  mutable std::unique_ptr<MapProcess> fine_;  // started by the first Jacobian
  mutable long jacobians_ = 0;                // Jacobians by the second instance so far
  mutable std::string jacobian_h_;            // the h of the last Jacobian, and its index there
  mutable long jacobian_step_ = 0;
  mutable R answer_noise_ = 0;     // a double program's answer noise at this h (noise_near)
  mutable std::string noise_key_;  // answer_noise's last (h, y) and what it measured there
  mutable T noise_ = 0;
  mutable T last_unit_ = 0;        // the last Jacobian's relative rounding (last_jacobian_unit)
  mutable double noise_in_ulps_ = -1;  // the largest relative noise noise_near measured, in double's ε
  mutable std::optional<std::pair<State<T, N>, Vector<T, N>>> last_;  // the last answer: (q, w), p
  mutable long evaluations_ = 0;  // the "evaluations" of every step's answer so far (extension)
  mutable long batch_ = 16;       // the steps the next request of steps() asks for (extension "steps")
  static constexpr long recheck = 8;
};

}  // namespace vivv

#include "harness/process/process_map_batches.hpp"      // the definitions of the batched requests above
#include "harness/process/process_map_differences.hpp"  // the definitions of the differences above
