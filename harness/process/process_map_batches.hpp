// How ProcessMap (harness/process/process_map.hpp) asks a program for several steps a request:
// the extension "steps" (the last state) and "trajectory" (every state), paced so that no answer
// comes near the timeout and no answer line grows past what vivv reads. The declarations and what
// each promises are in the class; here are their definitions.
#pragma once

#include <algorithm>
#include <chrono>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "harness/process/process_map.hpp"

namespace vivv {

template <LagrangianSystem System>
auto ProcessMap<System>::steps(const State<T, N>& x, const T& h, long count) const
    -> std::optional<State<T, N>> {
  if (!process_->uses_extension(steps_extension) || count < 2) return std::nullopt;
  return paced_batches(x, h, count, [&](const State<T, N>& from, long asked) {
    return batched_request(from, h, asked);
  });
}

template <LagrangianSystem System>
auto ProcessMap<System>::trajectory(const State<T, N>& x, const T& h, long count) const
    -> std::optional<std::vector<State<T, N>>> {
  if (!process_->uses_extension(steps_extension) ||
      !process_->uses_extension(trajectory_extension) || count < 2)
    return std::nullopt;
  std::vector<State<T, N>> states;
  states.reserve(static_cast<std::size_t>(count));
  // At most the states whose answer fits in the longest line vivv reads (program.cpp: 2n + (2n)²
  // numbers of D + 16 characters, twice for spaces), and in 8 MiB of text, so that an answer and
  // its parsed JSON stay small beside the case (at 114 coordinates and D = 17 about 1 100 states
  // a request; at 1000 coordinates about 130, still one round trip for many steps).
  const double per_state = (2 * n) * (digits_ + 16.0);
  const double line_states = (process_->longest_line() - 4096) / (2 * per_state) - 1;
  const long fitting =
      std::max(1L, static_cast<long>(std::min(line_states, 8.0 * 1024 * 1024 / per_state)));
  const auto end = paced_batches(
      x, h, count,
      [&](const State<T, N>& from, long asked) { return batched_states(from, h, asked, states); },
      fitting);
  if (!end) return std::nullopt;
  return states;
}

template <LagrangianSystem System>
template <class Request>
auto ProcessMap<System>::paced_batches(const State<T, N>& x, const T& h, long count, const Request& request,
                                       long at_most) const -> std::optional<State<T, N>> {
  State<T, N> state = x;
  const T start = time_;
  for (long left = count; left > 0;) {
    const long asked = std::min({left, batch_, at_most});
    const auto started = std::chrono::steady_clock::now();
    set_time(T(start + (count - left) * h));
    const std::optional<State<T, N>> next = request(state, asked);
    set_time(start);
    if (!next) return std::nullopt;
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    const double pace = std::min(1.0, options_.timeout_seconds / 10);
    const double paced = seconds > 0 ? asked * pace / seconds : 16.0 * asked;
    batch_ = std::max(1L, static_cast<long>(std::min(16.0 * asked, paced)));
    state = *next;
    left -= asked;
  }
  return state;
}

template <LagrangianSystem System>
auto ProcessMap<System>::batched_states(const State<T, N>& x, const T& h, long count,
                                        std::vector<State<T, N>>& states) const
    -> std::optional<State<T, N>> {
  const std::optional<nlohmann::json> answered = batch_answer(x, h, count, true);
  if (!answered) return std::nullopt;
  const nlohmann::json& answer = *answered;
  const long taken = count;
  const auto found = answer.find(trajectory_extension);
  const std::string expected =
      "an array of the " + std::to_string(taken) +
      " states its steps reached, each an array of 2n = " + std::to_string(2 * n) +
      " decimal strings (q, then p)";
  if (found == answer.end() || !found->is_array() ||
      found->size() != static_cast<std::size_t>(taken))
    process_->fail_answer(
        "it took up the extension \"trajectory\" and its answer's \"trajectory\" is " +
        (found == answer.end() ? std::string("missing") : quoted_text(found->dump(), 200)) +
        ", not " + expected);
  using std::abs;
  const T bound = scale_bound_in<T>();
  Vector<T, N> p_end(n);
  State<T, N> previous = x;
  for (long k = 0; k < taken; ++k) {
    const nlohmann::json& row = (*found)[static_cast<std::size_t>(k)];
    const std::string where = "trajectory[" + std::to_string(k) + "]";
    if (!row.is_array() || row.size() != static_cast<std::size_t>(2 * n))
      process_->fail_answer("its answer's \"" + where + "\" is " + quoted_text(row.dump(), 200) +
                            ", not " + std::to_string(2 * n) + " decimal strings (q, then p)");
    State<T, N> next{Vector<T, N>(n), Vector<T, N>(n)};
    for (int i = 0; i < n; ++i) {
      next.q[i] = answer_decimal<T>(*process_, row[static_cast<std::size_t>(i)],
                                    where + "[" + std::to_string(i) + "]", digits_);
      p_end[i] = answer_decimal<T>(*process_, row[static_cast<std::size_t>(n + i)],
                                   where + "[" + std::to_string(n + i) + "]", digits_);
      if (!(abs(next.q[i]) <= bound && abs(p_end[i]) <= bound)) return std::nullopt;
    }
    if (k + 1 == taken)
      for (int i = 0; i < n; ++i)
        if (answer_number<T>(*process_, answer, "q", i, n, digits_) != next.q[i] ||
            answer_number<T>(*process_, answer, "p", i, n, digits_) != p_end[i])
          process_->fail_answer(
              "its answer's last state in \"trajectory\" is not its \"q\" and \"p\" (entry " +
              std::to_string(i) + " differs)");
    try {  // from the state before's w, a step away; FL at the state's time
      next.w = at_system_time(T(time_ + (k + 1) * h), [&](const System& at) {
        return velocity_for_momentum(at, next.q, p_end, previous.w);
      });
    } catch (const SolverError&) {
      return std::nullopt;
    }
    states.push_back(next);
    previous = next;
  }
  last_ = {previous, p_end};
  return previous;
}

template <LagrangianSystem System>
auto ProcessMap<System>::batch_answer(const State<T, N>& x, const T& h, long count,
                                      bool every) const -> std::optional<nlohmann::json> {
  nlohmann::json request = state_request(x, h);
  request[steps_extension] = count;
  if (every) request[trajectory_extension] = true;
  nlohmann::json answer = process_->request(request);
  const long taken = answer_count(*process_, answer, steps_extension, count,
                                  "the count of steps it took (a whole number, 0 to the " +
                                      std::to_string(count) + " asked for)");
  count_evaluations(answer);
  if (taken < count) return std::nullopt;
  return answer;
}

template <LagrangianSystem System>
auto ProcessMap<System>::batched_request(const State<T, N>& x, const T& h, long count) const
    -> std::optional<State<T, N>> {
  const std::optional<nlohmann::json> answered = batch_answer(x, h, count, false);
  if (!answered) return std::nullopt;
  const nlohmann::json& answer = *answered;
  State<T, N> end{Vector<T, N>(n), Vector<T, N>(n)};
  Vector<T, N> p_end(n);
  using std::abs;
  const T bound = scale_bound_in<T>();
  for (int i = 0; i < n; ++i) {
    end.q[i] = answer_number<T>(*process_, answer, "q", i, n, digits_);
    p_end[i] = answer_number<T>(*process_, answer, "p", i, n, digits_);
    if (!(abs(end.q[i]) <= bound && abs(p_end[i]) <= bound)) return std::nullopt;
  }
  try {  // from x's w, steps away: where Newton does not converge from there, step by step
    end.w = at_system_time(T(time_ + count * h), [&](const System& at) {
      return velocity_for_momentum(at, end.q, p_end, x.w);
    });
  } catch (const SolverError&) {
    return std::nullopt;
  }
  last_ = {end, p_end};
  return end;
}

}  // namespace vivv
