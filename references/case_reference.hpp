// The reference a case runs against (harness/context/case_context.hpp): a closed-form flow where
// the case's system has one, the Taylor-series flow (references/taylor_reference.hpp) otherwise.
//
// The closed form is chosen at run time: the catalogue's harmonic oscillator, pendulum and Kepler
// problem run every claim through their formula twins, sized at run time like any formula system,
// and only their reference is their own (harness/context/reference_choice.hpp, catalogue_closed_form).
// No system type is compiled for it.
//
// Accuracy claimed, as for every reference: |y_i − F_t(start)_i| ≤ tolerance() (1 + |F_t(start)_i|);
// a closed form claims closed_form_tolerance (256 ε) and is cross-checked by the Taylor flow at
// 1000 ε, as ReferenceFlow (references/reference_flow.hpp) does for a system with a ClosedFormFlow.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/lagrangian/state.hpp"
#include "core/numerics/scalar.hpp"
#include "references/reference_flow.hpp"
#include "references/taylor_flow.hpp"
#include "references/taylor_reference.hpp"

namespace vivv {

template <TapeRecordable System>
class CaseReference {
 public:
  using Taylor = TaylorReference<System>;
  using T = typename Taylor::T;
  static constexpr int N = Taylor::N;
  using Answer = typename Taylor::Answer;

  // A closed form: F_t(start) and what it is, for the report.
  struct ClosedForm {
    std::function<State<T, N>(const State<T, N>&, const T&)> advance;
    std::string method;
  };

  // The Taylor flow at `tolerance` (raised to its floor, TaylorReference).
  CaseReference(System system, T tolerance) : system_(system), taylor_(Taylor(std::move(system), tolerance)) {}

  // The closed form `closed`, accurate to closed_form_tolerance.
  CaseReference(System system, ClosedForm closed)
      : system_(std::move(system)), closed_(std::make_shared<const ClosedForm>(std::move(closed))),
        check_progress_(std::make_shared<std::function<void(const T&, const T&)>>()) {
    if (!closed_->advance) throw std::invalid_argument("CaseReference: a closed form without a flow");
  }

  bool closed_form() const { return closed_ != nullptr; }
  const System& system() const { return system_; }

  // F_t(start) (t of either sign).
  State<T, N> advance(const State<T, N>& start, const T& t) const {
    return closed_ ? closed_->advance(start, t) : taylor_->advance(start, t);
  }

  // The accuracy claimed.
  T tolerance() const { return closed_ ? closed_form_tolerance<T>() : taylor_->tolerance(); }

  // ‖advance(start, t) − F̃_t(start)‖_max for an independent F̃: for a closed form the Taylor flow
  // at local tolerance check_floor() (1000 ε), for the Taylor flow its own rerun (TaylorReference).
  T estimate_error(const State<T, N>& start, const T& t) const {
    if (!closed_) return taylor_->estimate_error(start, t);
    TaylorFlow<System> check(system_, check_floor());
    check.integrator().on_progress = *check_progress_;
    return state_distance<T, N>(advance(start, t), check.advance(start, t));
  }

  // The Taylor flow begins its check on a thread of its own (TaylorReference::start_check); a
  // closed form's check runs in estimate_error.
  void start_check(const State<T, N>& start, const T& t) const {
    if (!closed_) taylor_->start_check(start, t);
  }

  // The global accuracy the check itself promises.
  T check_tolerance() const { return closed_ ? check_floor() * 1000000 : taylor_->check_tolerance(); }

  std::string method() const { return closed_ ? closed_->method : taylor_->method(); }

  // How tolerance() is backed up.
  std::string cross_check() const {
    return closed_ ? closed_form_cross_check<T>() : taylor_->cross_check();
  }

  // `report(reached, target)` after every step of the Taylor flow, `check_report` after every step
  // of a cross-check (a closed form has no steps of its own to report).
  void set_progress(std::function<void(const T&, const T&)> report,
                    std::function<void(const T&, const T&)> check_report = {}) const {
    if (closed_) *check_progress_ = std::move(check_report);
    else taylor_->set_progress(std::move(report), std::move(check_report));
  }

  // The answers a cache on disk keeps between runs (harness/context/reference_cache.hpp): the
  // Taylor flow's; a closed form costs nothing to recompute and keeps none.
  void keep_answers() const {
    if (!closed_) taylor_->keep_answers();
  }
  void recall(const std::vector<Answer>& advanced, const std::vector<Answer>& checked) const {
    if (!closed_) taylor_->recall(advanced, checked);
  }
  std::pair<std::vector<Answer>, std::vector<Answer>> answers() const {
    return closed_ ? std::pair<std::vector<Answer>, std::vector<Answer>>{} : taylor_->answers();
  }

  static T check_floor() { return closed_form_check_floor<T>(); }

 private:
  System system_;
  std::optional<Taylor> taylor_;
  std::shared_ptr<const ClosedForm> closed_;
  // The closed form's check progress, shared by copies (set_progress is const, as TaylorReference's).
  std::shared_ptr<std::function<void(const T&, const T&)>> check_progress_;
};

}  // namespace vivv
