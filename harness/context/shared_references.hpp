// One reference flow per system, scalar, precision and tolerance in a process: the cases of a run
// that integrate the same system share its flow — its trajectories, kept per initial state, and
// its cross-check, kept per initial state and T — instead of computing it once each (five cases
// on a 38-atom cluster computed the same reference five times, about 45 s each). A --refine
// round shares its case's. What is kept is what the cases still to run will ask for
// (keep_references, called by the run before each case: harness/command_line/workers.cpp); a
// process that never calls it (a unit test, the library) keeps nothing and each case makes its
// own. References are shared by copy: a TaylorReference's copies share one flow and its cache
// (references/taylor_reference.hpp).
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <typeinfo>
#include <utility>

#include "cases/case_file.hpp"

namespace vivv {

// What identifies a case's reference flow: the scalar it runs in (MPFR's digits with it), whether
// the tolerance is a double program's, the system as the case file writes it, its number of
// coordinates and every parameter's value. `spec` as it runs: --scalar and --digits applied.
std::string reference_key(const CaseSpec& spec);

// The keys of the cases this process will still run, the one about to run among them: a kept
// reference of another key is released, and one of these is kept once it is made.
void keep_references(const std::set<std::string>& keys);

// --reference-cache DIR: where reference flows keep their answers between runs (none: off).
void set_reference_cache(const std::optional<std::filesystem::path>& directory);
// The file of `key`'s answers in the cache — DIR/<hash>.json, the hash of the key and of this
// executable's bytes (another build may compute other last bits) — or none with the cache off.
std::optional<std::filesystem::path> reference_cache_file(const std::string& key);
// The executable's fingerprint in that hash (FNV-1a of its bytes, hexadecimal), written in the file.
const std::string& executable_fingerprint();

namespace detail {
// The reference kept under `typed` (null: none), and keeping `made` under it if `key` is wanted.
std::shared_ptr<const void> kept_reference(const std::string& typed);
void keep_reference(const std::string& typed, const std::string& key, std::shared_ptr<const void> made);
}  // namespace detail

// The reference of `key` made before in this process (then `kept` is set), or make()'s, kept if a
// case still to run may ask for it. Kept per Reference type too: one key's flow in two scalars
// never meets. What else follows from the reference alone (the derivative check of its flow at a
// state, run_system_impl.hpp) is kept the same way under its own `detail`, released with its key.
template <class Reference, class Make>
Reference shared_reference(const std::string& key, Make&& make, bool& kept_before, const std::string& detail = "") {
  const std::string typed = key + '\n' + typeid(Reference).name() + '\n' + detail;
  kept_before = false;
  if (std::shared_ptr<const void> kept = detail::kept_reference(typed)) {
    kept_before = true;
    return *static_cast<const Reference*>(kept.get());
  }
  auto made = std::make_shared<const Reference>(std::forward<Make>(make)());
  detail::keep_reference(typed, key, made);
  return *made;
}

}  // namespace vivv
