// The Taylor flow as the harness's reference: a drop-in for ReferenceFlow (issue 3).
//
// Same interface as ReferenceFlow (references/reference_flow.hpp) — advance,
// tolerance, method, cross_check, estimate_error — for every catalogue system,
// plus dense output: advance_many(start, times), and advance(start, t) itself
// evaluates the cached dense trajectory of `start`, so the many nearby times a
// sweep asks for (h = T/N for several N, Gauss nodes in [0, h]) cost one
// integration. Steps are never shortened, so the value at t depends only on
// (start, t), not on the order of the calls.
//
// Accuracy claimed, as for ReferenceFlow: |y_i − F_t(start)_i| ≤ tolerance() (1 + |F_t(start)_i|).
// The Jorba–Zou step tolerance is tolerance()·10⁻³: in the unit tests the
// global error of a pendulum orbit over 100 time units stays below 10⁻¹ of the
// step tolerance, so the factor 10⁻³ leaves a margin of 10⁴ for harder orbits.
// tolerance() is the requested one raised to the floor 10⁴ ε of the precision.
// Copies share the flow and its cached trajectories (thread-safe, one mutex).
#pragma once

#include <atomic>
#include <cmath>
#include <iomanip>
#include <functional>
#include <future>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/lagrangian/euler_lagrange_tape.hpp"
#include "core/numerics/scalar.hpp"
#include "core/lagrangian/state.hpp"
#include "references/taylor_flow.hpp"

namespace vivv {

template <TapeRecordable System>
class TaylorReference {
 public:
  using T = typename System::Scalar;
  static constexpr int N = System::dimension;
  static constexpr bool closed_form = false;

  // `tolerance`: the global accuracy wanted, raised to floor() if below it.
  TaylorReference(System system, T tolerance)
      : system_(std::move(system)), requested_tolerance_(std::move(tolerance)) {
    using std::max;
    if (!(requested_tolerance_ > 0))
      throw std::invalid_argument("TaylorReference: tolerance must be positive, got " +
                                  to_decimal<T>(requested_tolerance_));
    effective_tolerance_ = max(requested_tolerance_, floor());
    shared_ = std::make_shared<Shared>(system_, step_tolerance());
  }

  const System& system() const { return system_; }

  // Smallest tolerance claimed: 10⁴ ε.
  static T floor() { return 10000 * epsilon<T>(); }

  // The accuracy claimed.
  T tolerance() const { return effective_tolerance_; }

  // Jorba–Zou step tolerance: tolerance() / 1000.
  T step_tolerance() const { return effective_tolerance_ / 1000; }

  int order() const { return shared_->flow.order(); }

  // F_t(start) from the dense trajectory of `start` (t of either sign).
  State<T, N> advance(const State<T, N>& start, const T& t) const {
    std::lock_guard<std::mutex> lock(shared_->mutex);
    return answer(start, t, [&]() -> Cached& { return entry(start); });
  }

  // F_t(start) for every t of `times`, from the same cached trajectory.
  std::vector<State<T, N>> advance_many(const State<T, N>& start,
                                        const std::vector<T>& times) const {
    std::lock_guard<std::mutex> lock(shared_->mutex);
    Cached* cached = nullptr;  // looked up once, and only if an answer is not known
    std::vector<State<T, N>> states;
    states.reserve(times.size());
    for (const T& t : times)
      states.push_back(answer(start, t, [&]() -> Cached& { return cached ? *cached : *(cached = &entry(start)); }));
    return states;
  }

  // An answer of the flow: F_t(start) from `start`, or the check's state at `t` from `start`.
  struct Answer {
    State<T, N> start;
    T t;
    State<T, N> state;
  };

  // From now on every answer of advance is kept (the cross-check's are), for answers(): what a
  // cache on disk keeps between runs (harness/context/reference_cache.hpp).
  void keep_answers() const {
    std::lock_guard<std::mutex> lock(shared_->mutex);
    shared_->keeping = true;
  }

  // Answers this flow gave before, in an earlier run of the same executable, precision and system:
  // advance and estimate_error return them without integrating. Only a flow that computes to the
  // bit what it gave then may be told them (the cache's key says so).
  void recall(const std::vector<Answer>& advanced, const std::vector<Answer>& checked) const {
    std::lock_guard<std::mutex> lock(shared_->mutex);
    shared_->keeping = true;
    for (const Answer& a : advanced) shared_->answers.emplace(Asked{a.start, a.t}, a.state);
    for (const Answer& a : checked)
      if (!shared_->checked_state(a.start, a.t)) shared_->checked.push_back(a);
  }

  // Every answer kept (keep_answers, recall): advance's, and the cross-check's.
  std::pair<std::vector<Answer>, std::vector<Answer>> answers() const {
    std::lock_guard<std::mutex> lock(shared_->mutex);
    std::vector<Answer> advanced;
    for (const auto& [asked, state] : shared_->answers) advanced.push_back({asked.start, asked.t, state});
    return {advanced, {shared_->checked.begin(), shared_->checked.end()}};
  }

  // ‖advance(start, t) − F̃_t(start)‖_max with F̃ an independent Taylor run (higher order, other
  // steps) at step tolerance check_step_tolerance(), of order check_order(): the one
  // start_check(start, t) began, or one run here.
  // A check once done is kept (copies share it: the cases of a run that share this flow,
  // harness/context/shared_references.hpp, check it once).
  T estimate_error(const State<T, N>& start, const T& t) const {
    std::future<State<T, N>> begun;
    std::optional<State<T, N>> done;
    {
      std::lock_guard<std::mutex> lock(shared_->mutex);
      done = shared_->checked_state(start, t);
      if (!done && shared_->check.valid() && same_state(shared_->check_start, start) && shared_->check_end == t)
        begun = std::move(shared_->check);
    }
    if (!done) {
      done = begun.valid() ? begun.get() : check_flow()->advance(start, t);
      std::lock_guard<std::mutex> lock(shared_->mutex);
      shared_->checked.push_front({start, t, *done});
      if (shared_->checked.size() > 8) shared_->checked.pop_back();
    }
    return state_distance<T, N>(advance(start, t), *done);
  }

  // Begins the check's integration from `start` to `t` on a thread of its own, beside whatever this
  // thread does next (the flow's own integration to t): two independent integrations of about the
  // same cost take the time of one on two cores. estimate_error(start, t) waits for it and
  // rethrows what it threw. A reference destroyed first stops it at its next step (a case refused
  // meanwhile does not wait for it). Not in MPFR: Boost 1.74 keeps MPFR's default precision per
  // process, and this thread may change it while the check computes (ProcessMap's decimals), so
  // an MPFR check runs in estimate_error, after the flow.
  void start_check(const State<T, N>& start, const T& t) const {
    if constexpr (!is_mpfr_v<T>) {
      std::shared_ptr<TaylorFlow<System>> flow = check_flow();  // recorded here, integrated there
      std::lock_guard<std::mutex> lock(shared_->mutex);
      if (shared_->check.valid() || shared_->checked_state(start, t)) return;
      shared_->check_start = start;
      shared_->check_end = t;
      shared_->check = std::async(std::launch::async, [flow, start, t] { return flow->advance(start, t); });
    }
  }

  // The global accuracy the check itself promises, by this flow's own rule
  // (step tolerance = tolerance · 10⁻³).
  T check_tolerance() const { return check_step_tolerance() * 1000; }

  // e.g. "Taylor series, order 85 (Jorba–Zou), tol 1e-70".
  std::string method() const {
    std::string text = "Taylor series of the Euler–Lagrange field by Taylor-mode AD, order " +
                       std::to_string(order()) + " (Jorba–Zou steps, step tolerance " +
                       three_digits(step_tolerance()) + "), tol " +
                       three_digits(effective_tolerance_);
    if (effective_tolerance_ > requested_tolerance_)
      text += " (requested " + three_digits(requested_tolerance_) + ", below the floor of 10⁴ ulps of " +
              scalar_name<T>() + ")";
    return text;
  }

  // How tolerance() is backed up.
  std::string cross_check() const {
    return "unit tests compare the Taylor flow with the closed forms (harmonic oscillator, "
           "pendulum) in quad and at 200 and 400 bits, run it forward and back, against a run at "
           "+64 bits and tol·1e-20, and check energy conservation for every catalogue system; "
           "estimate_error(v, t) reruns the Taylor flow at step tolerance " +
           three_digits(check_step_tolerance()) + " (order " + std::to_string(check_order()) +
           (check_step_tolerance() < step_tolerance()
                ? ""
                : ": at the floor of " + scalar_name<T>() + " the step tolerance cannot go below the flow's, so "
                  "the check takes 6 orders more, and other steps") +
           ") and reports the max-norm difference";
  }

  // The check's order: Jorba–Zou's for its step tolerance, or, where that tolerance is the
  // flow's own (the floor 10 ε of a hardware scalar: double, long double, float128), 6 more. A
  // check of the flow's tolerance and order takes the same steps and agrees to the bit: it
  // reported 0 and checked nothing.
  int check_order() const {
    return check_step_tolerance() < step_tolerance() ? taylor_order_for(check_step_tolerance()) : order() + 6;
  }

  // `report(reached, target)` after every step of the flow, and `check_report` after every step
  // of its check (copies of this reference share them): the check's progress under its own
  // name, not read as the flow starting again. A case that shares the flow with later ones
  // clears them when it ends (set_progress({})): once this returns, neither is called again.
  void set_progress(std::function<void(const T&, const T&)> report,
                    std::function<void(const T&, const T&)> check_report = {}) const {
    std::lock_guard<std::mutex> lock(shared_->mutex);
    shared_->flow.integrator().on_progress = std::move(report);
    std::lock_guard<std::mutex> progress_lock(shared_->progress_mutex);
    shared_->check_progress = std::move(check_report);
  }

  // Work so far: steps, order, multiply-adds of the cached trajectories.
  TaylorReport report() const {
    std::lock_guard<std::mutex> lock(shared_->mutex);
    return shared_->flow.report();
  }

 private:
  // The dense trajectories of one start, forward and backward, extended on demand.
  struct Cached {
    State<T, N> start;
    TaylorTrajectory<T> forward, backward;
    std::vector<T> state_at(const T& t, TaylorFlow<System>& flow) {
      TaylorTrajectory<T>& trajectory = t >= 0 ? forward : backward;
      if (!trajectory.covers(t)) flow.integrator().extend(trajectory, t);
      return trajectory.state_at(t);
    }
  };

  using Index = Eigen::Index;

  // A question to the flow, ordered by t and then the start's entries (exact comparisons).
  struct Asked {
    State<T, N> start;
    T t;
  };
  struct AskedOrder {
    bool operator()(const Asked& a, const Asked& b) const {
      if (a.t != b.t) return a.t < b.t;
      for (Index i = 0; i < a.start.q.size(); ++i)
        if (a.start.q[i] != b.start.q[i]) return a.start.q[i] < b.start.q[i];
      for (Index i = 0; i < a.start.w.size(); ++i)
        if (a.start.w[i] != b.start.w[i]) return a.start.w[i] < b.start.w[i];
      return false;
    }
  };
  // F_t(start): the answer kept, or the trajectory's (trajectory() finds it), kept if answers are.
  // Called with the mutex held.
  template <class Trajectory>
  State<T, N> answer(const State<T, N>& start, const T& t, Trajectory&& trajectory) const {
    if (shared_->keeping) {
      if (auto known = shared_->answers.find(Asked{start, t}); known != shared_->answers.end()) return known->second;
    }
    State<T, N> state = shared_->flow.state_of(trajectory().state_at(t, shared_->flow));
    if (shared_->keeping) shared_->answers.emplace(Asked{start, t}, state);
    return state;
  }

  // The flow and the trajectories computed so far, shared by copies of the reference.
  struct Shared {
    Shared(const System& system, const T& step_tolerance) : flow(system, step_tolerance) {}
    // A check still running is told to stop (at its next step) and waited for: it reads
    // check_progress and cancelled.
    ~Shared() {
      cancelled = true;
      if (check.valid()) check.wait();
    }
    // The check's end state from `start` to `end`, if a check of them is done.
    std::optional<State<T, N>> checked_state(const State<T, N>& start, const T& end) const {
      for (const Answer& c : checked)
        if (same_state(c.start, start) && c.t == end) return c.state;
      return std::nullopt;
    }
    std::mutex mutex;
    TaylorFlow<System> flow;
    // The cross-check's (set_progress), called under its own mutex from the check's thread, which
    // `mutex` would hold up while the flow integrates.
    std::mutex progress_mutex;
    std::function<void(const T&, const T&)> check_progress;
    std::list<Cached> cache;  // most recently used first
    std::atomic<bool> cancelled{false};
    State<T, N> check_start;  // the check start_check began, from check_start to check_end
    T check_end = 0;
    std::future<State<T, N>> check;
    std::list<Answer> checked;  // the checks done, most recent first (eight kept; the check's end is t)
    bool keeping = false;                               // keep_answers, recall
    std::map<Asked, State<T, N>, AskedOrder> answers;  // advance's, while keeping
  };

  static bool same_state(const State<T, N>& a, const State<T, N>& b) { return a.q == b.q && a.w == b.w; }

  // Thrown by a check's progress when its reference is gone (Shared's destructor).
  struct CheckCancelled {};

  // The independent check's flow, its progress reported as the cross-check's (and stopped when
  // the reference is destroyed).
  std::shared_ptr<TaylorFlow<System>> check_flow() const {
    auto flow = std::make_shared<TaylorFlow<System>>(system_, check_step_tolerance(), check_order());
    flow->integrator().on_progress = [shared = shared_.get()](const T& reached, const T& target) {
      if (shared->cancelled) throw CheckCancelled{};
      std::lock_guard<std::mutex> lock(shared->progress_mutex);
      if (shared->check_progress) shared->check_progress(reached, target);
    };
    return flow;
  }


  // The cache entry of `start` (the eight most recent starts are kept).
  Cached& entry(const State<T, N>& start) const {
    std::list<Cached>& cache = shared_->cache;
    for (auto it = cache.begin(); it != cache.end(); ++it) {
      if (same_state(it->start, start)) {
        cache.splice(cache.begin(), cache, it);
        return cache.front();
      }
    }
    auto y = shared_->flow.components(start);
    cache.push_front(Cached{start, TaylorTrajectory<T>(y, 1), TaylorTrajectory<T>(y, -1)});
    if (cache.size() > 8) cache.pop_back();
    return cache.front();
  }

  // Step tolerance of the independent check: 10⁻⁴ of the flow's, at least 10 ε. The check then
  // errs by at most 10⁻⁴ of what the flow may, so its distance from the flow is the flow's error
  // to 10⁻⁴ of the tolerance — all the estimate is for; 10⁻¹⁰ (before) bought nothing more and
  // cost a higher order (on the 114-coordinate LJ38 case, 45 % more time than the flow itself).
  T check_step_tolerance() const {
    using std::max;
    return max(T(step_tolerance() / 10000), T(10 * epsilon<T>()));
  }

  System system_;
  T requested_tolerance_;
  T effective_tolerance_;
  std::shared_ptr<Shared> shared_;
};

}  // namespace vivv
