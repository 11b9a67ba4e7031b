// The catalogue: system names to system types, and the vocabulary of case files.
//
// `visit_system<T>(name, parameters, f)` builds the named system in scalar T
// and calls the generic f(system); this is where run-time names meet the
// compile-time system types of cases/systems.hpp.
#pragma once

#include <stdexcept>
#include <string>
#include <optional>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

#include "cases/systems.hpp"
#include "core/structure/noether.hpp"
#include "core/numerics/scalar.hpp"

namespace vivv {

// Every catalogue system, instantiated at scalar T.
template <class T>
using CatalogueSystems = std::tuple<PaperExample<T>, HarmonicOscillator<T>, Pendulum<T>,
                                    RelativisticParticle<T>, ChargedParticle<T>, Kepler<T>, HenonHeiles<T>,
                                    DoublePendulum<T>>;

// Claim ids a case may ask for (docs/claims.md); harness/claims/registry.hpp implements each.
inline const std::vector<std::string>& claim_ids() {
  static const std::vector<std::string> ids = {
      "global-order",       "lagrangian-order",    "legendre-order", "twin-term-invariance",
      "mismatched-legendre", "order",              "contact-order",  "qxq-tq-equivalence",
      "existence-uniqueness", "exact-discretization", "past-future-symmetry", "symplecticity",
      "discrete-noether",   "energy-behaviour",    "energy-balance",  "modified-energy",
      "precision-leak",     "local-order"};
  return ids;
}

// Claims stated for Q×Q discrete Lagrangians only.
inline const std::set<std::string>& qxq_claim_ids() {
  static const std::set<std::string> ids = {"lagrangian-order", "legendre-order",
                                            "mismatched-legendre", "symplecticity",
                                            "discrete-noether", "energy-behaviour", "modified-energy"};
  return ids;
}

// Claims stated for discretizations of TQ only (paper §4–6).
inline const std::set<std::string>& tq_claim_ids() {
  static const std::set<std::string> ids = {"order", "contact-order", "qxq-tq-equivalence",
                                            "existence-uniqueness", "exact-discretization", "past-future-symmetry"};
  return ids;
}

// Claims that apply to a one-step map (discretization kind "odeint"): the others are about
// the discrete Lagrangian a map does not have.
inline const std::set<std::string>& map_claim_ids() {
  static const std::set<std::string> ids = {"global-order", "local-order", "symplecticity", "energy-behaviour",
                                            "energy-balance", "discrete-noether", "precision-leak"};
  return ids;
}

struct SystemInfo {
  std::string name;
  int dimension;
  std::vector<ParameterSpec> parameters;
  bool symmetric = false;  // declares a symmetry (core/structure/noether.hpp)
};

// Name, dimension and parameters of every catalogue system.
inline std::vector<SystemInfo> system_catalogue() {
  std::vector<SystemInfo> info;
  std::apply(
      [&](auto... system) {
        (info.push_back({decltype(system)::name, decltype(system)::dimension,
                         decltype(system)::parameters(), DeclaresSymmetry<decltype(system)>}),
         ...);
      },
      CatalogueSystems<double>{});
  return info;
}

// Builds the system `name` in scalar T with `parameters` (decimal strings in
// the order of its ParameterSpec list) and returns f(system); `Systems`, a tuple of some of
// the catalogue's systems in T, are the candidates (an instantiation of f for each).
template <class T, class Systems = CatalogueSystems<T>, class F>
auto visit_system(const std::string& name, const std::vector<std::string>& parameters,
                            F&& f) {
  return std::apply(
      [&](auto... candidates) {
        using Result = decltype(f(std::get<0>(Systems{})));
        if constexpr (std::is_void_v<Result>) {
          bool found = false;
          (
              [&](auto system) {
                if (found || name != decltype(system)::name) return;
                found = true;
                std::vector<T> values;
                for (const auto& p : parameters) values.push_back(from_decimal<T>(p));
                system.set(values);
                f(system);
              }(candidates),
              ...);
          if (!found) throw std::invalid_argument("unknown system '" + name + "'");
        } else {
          std::optional<Result> result;
          (
              [&](auto system) {
                if (result || name != decltype(system)::name) return;
                std::vector<T> values;
                for (const auto& p : parameters) values.push_back(from_decimal<T>(p));
                system.set(values);
                result.emplace(f(system));
              }(candidates),
              ...);
          if (!result) throw std::invalid_argument("unknown system '" + name + "'");
          return std::move(*result);
        }
      },
      Systems{});
}

}  // namespace vivv
