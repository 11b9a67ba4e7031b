// Where a one-step error sits: the coordinates that carry most of it, named as the case names them
// (a family's member "x[1,2]", a whole family row "x[1,*]", or q[i] for a catalogue system). A map
// that steps another system than the case's — a mass, a parameter, a unit or a force term of its
// own — errs by h·(f̃ − f) in one step: an error of order 1 (global order 0), and it sits where f̃
// and f differ. local-order names those coordinates beside its verdict (harness/claims/
// map_local_order.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace vivv {

// The coordinates' shares of a one-step error. `squared[i]`: the squared error of coordinate i (its
// q and p together), summed over the states measured, each state's errors first divided by its
// largest so that every state counts alike.
struct ErrorLocation {
  std::vector<std::string> names;  // the fewest groups (a family's row x[1,*], or a coordinate) carrying `share`
  double share = 0;
  bool concentrated = false;  // they are at most a quarter of the groups (and at most 8 names)
  nlohmann::json by_coordinate = nlohmann::json::array();  // the 8 largest shares, for report.json
};

// The row a family member belongs to: "x[1" of "x[1,2]" (a body of a many-body family); empty
// for a plain name or a one-index family's member, which is its own group.
inline std::string row_of(const std::string& name) {
  const std::size_t comma = name.rfind(',');
  return comma == std::string::npos || name.back() != ']' ? std::string() : name.substr(0, comma);
}

// The error is located by groups — a family's rows (a body's coordinates x[1,*] together), every
// other coordinate alone — as the fewest groups carrying 90 % of the squared error.
inline ErrorLocation locate_error(const std::vector<double>& squared, const std::vector<std::string>& names) {
  ErrorLocation where;
  const double total = std::accumulate(squared.begin(), squared.end(), 0.0);
  if (!(total > 0) || !std::isfinite(total) || squared.size() != names.size()) return where;
  std::vector<std::string> group_names;
  std::map<std::string, std::size_t> group_of;
  std::vector<double> group_squared;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string row = row_of(names[i]);
    const std::string key = row.empty() ? names[i] : row + ",*]";
    const auto [it, fresh] = group_of.emplace(key, group_names.size());
    if (fresh) group_names.push_back(key), group_squared.push_back(0);
    group_squared[it->second] += squared[i];
  }
  std::vector<int> order(group_names.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return group_squared[a] > group_squared[b]; });
  double carried = 0;
  for (const int g : order) {
    if (carried >= 0.9 * total) break;
    where.names.push_back(group_names[g]);
    carried += group_squared[g];
  }
  std::vector<int> coordinates(squared.size());
  std::iota(coordinates.begin(), coordinates.end(), 0);
  std::stable_sort(coordinates.begin(), coordinates.end(), [&](int a, int b) { return squared[a] > squared[b]; });
  for (std::size_t k = 0; k < coordinates.size() && k < 8; ++k)
    where.by_coordinate.push_back({{"coordinate", names[coordinates[k]]}, {"share", squared[coordinates[k]] / total}});
  where.share = carried / total;
  where.concentrated = where.names.size() <= 8 && 4 * where.names.size() <= group_names.size();
  return where;
}

// "x[1,*] (94 % of it)", or "" where the error is spread over many coordinates.
inline std::string error_location_words(const ErrorLocation& where) {
  if (!where.concentrated || where.names.empty()) return {};
  std::string names;
  for (const std::string& name : where.names) names += (names.empty() ? "" : ", ") + name;
  return names + " (" + std::to_string(static_cast<int>(std::lround(100 * where.share))) + " % of it)";
}

}  // namespace vivv
