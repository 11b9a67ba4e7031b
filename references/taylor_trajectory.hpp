// Dense output of the Taylor flow: the solution as the piecewise Taylor polynomial of its steps.
//
// Step s covers [t_s, t_s + h_s] (h_s < 0 backward in time) and stores the
// normalized coefficients y_{s,k} of every component y = (x, v), so that
//   y(t) = Σ_{k=0..p} y_{s,k} (t − t_s)^k     for t in the step   (Horner),
// accurate to the step tolerance inside the step as at its end. A trajectory
// runs from time 0 in one direction; TaylorFlow keeps one per direction.
#pragma once

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/numerics/scalar.hpp"
#include "core/autodiff/taylor_expansion.hpp"  // taylor_detail::set_mul, set_add

namespace vivv {

template <class T>
struct TaylorStep {
  T start;                     // t_s
  T length;                    // h_s, signed
  int order = 0;               // p
  std::vector<T> coefficients;  // component c, order k at [c (p + 1) + k]
};

template <class T>
class TaylorTrajectory {
 public:
  TaylorTrajectory() = default;
  // A trajectory of `components` values y starting at time 0 from y0, in direction ±1.
  TaylorTrajectory(std::vector<T> y0, int direction)
      : direction_(direction), start_state_(std::move(y0)), end_state_(start_state_) {}

  int direction() const { return direction_; }
  int components() const { return static_cast<int>(start_state_.size()); }
  const std::vector<TaylorStep<T>>& steps() const { return steps_; }
  // The time the trajectory reaches: 0 plus the step lengths.
  const T& end_time() const { return end_time_; }
  // y at end_time().
  const std::vector<T>& end_state() const { return end_state_; }
  const std::vector<T>& start_state() const { return start_state_; }

  // Whether t lies in [0, end_time()] (or [end_time(), 0] backward).
  bool covers(const T& t) const {
    return direction_ > 0 ? (t >= 0 && t <= end_time_) : (t <= 0 && t >= end_time_);
  }

  // Appends a step whose polynomial ends at `end_state`.
  void append(TaylorStep<T> step, std::vector<T> end_state) {
    end_time_ = step.start + step.length;
    end_state_ = std::move(end_state);
    steps_.push_back(std::move(step));
  }

  // y(t) = Σ_k y_{s,k} (t − t_s)^k in the step s that contains t (Horner).
  std::vector<T> state_at(const T& t) const {
    if (!covers(t))
      throw std::out_of_range("TaylorTrajectory: t = " + to_decimal<T>(t) +
                              " is outside the integrated range [0, " + to_decimal<T>(end_time_) +
                              "]");
    if (t == 0) return start_state_;
    // The first step whose end is at or beyond t (step ends are monotone: binary search).
    auto before = [&](const TaylorStep<T>& step) {
      T end = step.start + step.length;
      return direction_ > 0 ? end < t : end > t;
    };
    auto found = std::partition_point(steps_.begin(), steps_.end(), before);
    if (found == steps_.end()) return end_state_;
    return evaluate(*found, T(t - found->start));
  }

  // Σ_k y_k τ^k for every component of `step`.
  static std::vector<T> evaluate(const TaylorStep<T>& step, const T& tau) {
    const int stride = step.order + 1;
    const int count = static_cast<int>(step.coefficients.size()) / stride;
    std::vector<T> y(count);
    for (int c = 0; c < count; ++c) {
      const T* coefficient = step.coefficients.data() + c * stride;
      T& sum = y[c];
      sum = coefficient[step.order];
      for (int k = step.order - 1; k >= 0; --k) {
        taylor_detail::set_mul(sum, sum, tau);  // in place: no temporaries for MPFR
        taylor_detail::set_add(sum, sum, coefficient[k]);
      }
    }
    return y;
  }

 private:
  int direction_ = 1;
  std::vector<T> start_state_;
  std::vector<T> end_state_;
  T end_time_ = 0;
  std::vector<TaylorStep<T>> steps_;
};

}  // namespace vivv
