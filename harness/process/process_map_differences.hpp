// How ProcessMap (harness/process/process_map.hpp) measures a program's derivatives: central
// differences of its steps along directions (a coordinate's column, or a probe's vector), the
// second instance's differences and their padded-digits checks, the program's own Jacobian
// checked against differences, and the noise of a double program's answers. The declarations and
// what each promises are in the class; here are their definitions.
#pragma once

#include <algorithm>
#include <array>
#include <deque>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "harness/process/process_map.hpp"

namespace vivv {

template <LagrangianSystem System>
template <class Direction>
typename ProcessMap<System>::Differences ProcessMap<System>::along(MapProcess& process, int digits,
                                                                   const std::string& step,
                                                                   const std::vector<std::string>& y, int count,
                                                                   const Direction& direction, int exponent,
                                                                   const T& h, int multiple) const {
  using std::abs, std::max, std::pow;
  Differences result(static_cast<std::size_t>(count), std::vector<R>(2 * n));
  std::vector<R> centre(2 * n);
  for (int j = 0; j < 2 * n; ++j) centre[j] = from_decimal<R>(y[j]);
  // Requests made as the program takes them (MapProcess::requests: one that took up "pipeline"
  // works on one while vivv reads the last answer and makes the next), each direction's two in turn.
  int k = -1, side = 1;  // the request made last: direction k, from y + δu (side 0) or y − δu (1)
  std::vector<R> u;
  R delta = 0;
  std::deque<std::pair<int, R>> sent;  // each request's direction and δ, in order, unanswered
  const auto next = [&]() -> std::optional<nlohmann::json> {
    if (side == 1) {  // the next direction that is not 0 (J·0 = 0)
      for (side = 0, ++k; k < count; ++k) {
        u = direction(k);
        // the entry that sets the scale: the largest |u_j| / max(1, |y_j|)
        int widest = -1;
        R ratio = 0;
        for (int j = 0; j < 2 * n; ++j) {
          const R r = R(abs(u[j])) / max(R(1), R(abs(centre[j])));
          if (r > ratio) ratio = r, widest = j;
        }
        if (widest < 0) continue;
        const R scale = max(R(1), R(abs(centre[widest]))) / R(abs(u[widest]));
        delta = multiple * pow(R(10), -exponent) * scale;
        break;
      }
      if (k >= count) return std::nullopt;
    } else {
      side = 1;
    }
    nlohmann::json request = {{"h", step}, {"q", nlohmann::json::array()}, {"p", nlohmann::json::array()}};
    for (int i = 0; i < 2 * n; ++i) {
      const auto moved = [&] { return side == 0 ? R(centre[i] + delta * u[i]) : R(centre[i] - delta * u[i]); };
      // A double program gets the double it would read from R's decimal (double_decimal).
      request[i < n ? "q" : "p"].push_back(u[i] == 0        ? y[i]
                                           : double_program_ ? double_decimal(static_cast<double>(moved()))
                                                             : to_decimal<R>(moved()));
    }
    sent.emplace_back(k, delta);
    return request;
  };
  std::vector<R> image_plus;  // the step from y + δu; the next answer is the one from y − δu
  bool minus = false;
  process.requests(next, [&](const nlohmann::json& answer) {
    std::vector<R> image = double_program_ ? double_answer(process, answer, h) : answer_state<R>(process, answer, digits, h);
    const auto [direction_index, width] = sent.front();
    sent.pop_front();
    if (!minus) {
      image_plus = std::move(image);
    } else {
      for (int i = 0; i < 2 * n; ++i)
        result[direction_index][i] = (image_plus[i] - image[i]) / (2 * width);
    }
    minus = !minus;
  });
  return result;
}

template <LagrangianSystem System>
template <class Direction>
typename ProcessMap<System>::Differences ProcessMap<System>::fine_along(const std::vector<std::string>& y,
                                                                        const std::string& step, const T& h,
                                                                        int count, const Direction& direction,
                                                                        const std::string& epsilon_of_T) const {
  if (!fine_) fine_ = start(fine_digits());
  // The first Jacobian and every `recheck`-th one are computed again at 10 times the width: a
  // program computing at the digits it was asked for gives the same matrix to about
  // 10^(−(4D+14)/3) (the width's truncation grows 100 times), far below ε of the working
  // precision; one that computes in fewer digits and pads its answers differs by its own
  // rounding over the width, and the Jacobian would measure that instead of the map.
  const bool check = jacobians_++ % recheck == 0;
  using std::abs, std::max, std::pow;
  const auto narrow = along(*fine_, fine_digits(), step, y, count, direction, difference_exponent(), h);
  if (check) {
    // Against a coarse width 10^(-ceil(D/3)) too, which a program computing in fewer digits
    // still resolves: padding below its precision makes both narrow widths see no change at
    // all (a zero column agrees with itself). At the coarse width the truncation is about
    // 10^(-2D/3) times the map's third derivative; a change above 10^(-ceil(D/6))·|J| would
    // need a third derivative near 10^(D/2).
    const auto wide = along(*fine_, fine_digits(), step, y, count, direction, difference_exponent() - 1, h);
    const auto coarse = along(*fine_, fine_digits(), step, y, count, direction, coarse_exponent(), h);
    R largest = 1, change = 0, coarse_change = 0;
    for (int j = 0; j < count; ++j)
      for (int i = 0; i < 2 * n; ++i)
        largest = max(largest, R(abs(narrow[j][i]))),
        change = max(change, R(abs(narrow[j][i] - wide[j][i]))),
        coarse_change = max(coarse_change, R(abs(narrow[j][i] - coarse[j][i])));
    if (!(coarse_change <= pow(R(10), -((coarse_exponent() + 1) / 2)) * largest))
      unmeasurable("its Jacobian by central differences at width 10^-" +
                   std::to_string(difference_exponent()) + " differs by " +
                   to_decimal<R>(coarse_change, 3) + " from the one at width 10^-" +
                   std::to_string(coarse_exponent()) + " (|J| = " + to_decimal<R>(largest, 3) +
                   ")");
    if (!(change <= from_decimal<R>(epsilon_of_T) * largest))
      unmeasurable("its Jacobian by central differences changes by " +
                   to_decimal<R>(change, 3) + " between widths 10^-" +
                   std::to_string(difference_exponent()) + " and 10^-" +
                   std::to_string(difference_exponent() - 1) +
                   ", more than the working precision's epsilon " +
                   to_decimal<R>(from_decimal<R>(epsilon_of_T), 3) + " times |J| = " +
                   to_decimal<R>(largest, 3));
  }
  return narrow;
}

template <LagrangianSystem System>
auto ProcessMap<System>::own_jacobian(const std::vector<std::string>& y, const T& h,
                                       long step_index) const -> Matrix<T, twice(N), twice(N)> {
  nlohmann::json request = {{"h", to_decimal<T>(h)},
                            {"q", nlohmann::json::array()},
                            {"p", nlohmann::json::array()},
                            {jacobian_extension, true}};  // the answer must carry it
  for (int i = 0; i < 2 * n; ++i) request[i < n ? "q" : "p"].push_back(y[i]);
  const nlohmann::json answer = process_->request(request);
  const std::size_t size = 2 * n;
  if (!answer.contains(jacobian_extension) || !answer[jacobian_extension].is_array() ||
      answer[jacobian_extension].size() != size)
    process_->fail_answer(
        "it took up the extension \"jacobian\" and its answer has no \"jacobian\" of " +
        std::to_string(size) + " rows (got " +
        (answer.contains(jacobian_extension) ? quoted_text(answer[jacobian_extension].dump(), 200)
                                             : std::string("none")) +
        ")");
  Matrix<T, twice(N), twice(N)> jacobian(2 * n, 2 * n);
  for (int i = 0; i < 2 * n; ++i) {
    const nlohmann::json& row = answer[jacobian_extension][static_cast<std::size_t>(i)];
    if (!row.is_array() || row.size() != size)
      process_->fail_answer("jacobian[" + std::to_string(i) + "] is " + quoted_text(row.dump(), 200) +
                            ", not a row of " + std::to_string(size) + " decimal strings");
    for (int j = 0; j < 2 * n; ++j)
      jacobian(i, j) = answer_decimal<T>(*process_, row[static_cast<std::size_t>(j)],
                                  "jacobian[" + std::to_string(i) + "][" + std::to_string(j) + "]",
                                  digits_);
  }
  const long answered = process_->requests();
  if (step_index % recheck != 0) return jacobian;
  PrecisionGuard guard(digits_ + 10);
  using std::abs, std::max, std::pow;
  const std::string step = to_decimal<T>(h);
  const auto coarse = differences(*process_, digits_, step, y, coarse_exponent(), h);
  const auto coarser = differences(*process_, digits_, step, y, coarse_exponent() - 1, h);
  R largest = 1;
  for (int j = 0; j < 2 * n; ++j)
    for (int i = 0; i < 2 * n; ++i) largest = max(largest, R(abs(coarse[j][i])));
  const R rounding = 100 * pow(R(10), coarse_exponent() - digits_) * largest;
  for (int j = 0; j < 2 * n; ++j)
    for (int i = 0; i < 2 * n; ++i) {
      const R own = from_decimal<R>(to_decimal<T>(jacobian(i, j)));
      const R allowed = 4 * R(abs(coarse[j][i] - coarser[j][i])) + rounding;
      if (!(abs(own - coarse[j][i]) <= allowed))
        throw UnmeasurableJacobian(
            "the map program " + name() + " sent a wrong Jacobian (extension \"jacobian\") at h = " +
            shortest(h) + ", step " + std::to_string(step_index) + " of that run (request " +
            std::to_string(answered) + "): entry jacobian[" + std::to_string(i) + "][" +
            std::to_string(j) + "] = d" + (i < n ? "q'" : "p'") + "[" + std::to_string(i % n) +
            "]/d" + (j < n ? "q" : "p") + "[" + std::to_string(j % n) + "] is " +
            to_decimal<R>(own, 10) + ", while central differences of its own steps at width 10^-" +
            std::to_string(coarse_exponent()) + " give " + to_decimal<R>(coarse[j][i], 10) +
            " (they may differ by " + to_decimal<R>(allowed, 3) +
            "): symplecticity would judge a matrix that is not the map's derivative");
    }
  return jacobian;
}

template <LagrangianSystem System>
typename ProcessMap<System>::R ProcessMap<System>::noise_near(const std::string& step,
                                                              const std::vector<std::string>& y,
                                                              const T& h) const {
  using std::abs, std::max, std::pow, std::sqrt;
  const auto image = [&](const std::vector<R>& at) {
    nlohmann::json request = {{"h", step}, {"q", nlohmann::json::array()}, {"p", nlohmann::json::array()}};
    for (int i = 0; i < 2 * n; ++i) request[i < n ? "q" : "p"].push_back(double_decimal(static_cast<double>(at[i])));
    return double_answer(*process_, process_->request(request), h);
  };
  std::vector<R> centre(2 * n);
  for (int j = 0; j < 2 * n; ++j) centre[j] = from_decimal<R>(y[j]);
  const std::vector<R> f0 = image(centre);
  R noise = 0;
  for (const int exponent : {digits_ / 2, double_exponent() + 2}) {
    const R spacing = pow(R(10), -exponent);
    for (int direction = 0; direction < 4; ++direction) {
      // (1, 1, …), (1, −1, …), q alone, p alone
      const auto component = [&](int j) {
        return direction == 0 ? 1 : direction == 1 ? (j % 2 ? -1 : 1) : (j < n) == (direction == 2) ? 1 : 0;
      };
      std::array<std::vector<R>, 4> f;  // at k = −2, −1, 1, 2
      const int ks[4] = {-2, -1, 1, 2};
      for (int m = 0; m < 4; ++m) {
        std::vector<R> at = centre;
        for (int j = 0; j < 2 * n; ++j) at[j] += ks[m] * spacing * max(R(1), R(abs(centre[j]))) * component(j);
        f[m] = image(at);
      }
      for (int i = 0; i < 2 * n; ++i) {
        const R spread = R(abs(R(f[0][i] - 4 * f[1][i] + 6 * f0[i] - 4 * f[2][i] + f[3][i]))) / sqrt(R(70));
        noise = max(noise, spread);
        noise_in_ulps_ = std::max(noise_in_ulps_, static_cast<double>(spread / max(R(1), R(abs(f0[i])))) /
                                                      std::numeric_limits<double>::epsilon());
      }
    }
  }
  return noise;
}

}  // namespace vivv
