// --reference-cache DIR (opt-in): a Taylor reference flow's answers kept on disk between runs, so
// that a case run again — its program edited, a pytest -k or --lf — does not integrate the same
// reference again. What is kept is every answer the flow gave: F_t(x) for each (x, t) asked, and the
// cross-check's state at T, each number to the digits that read back to the same bits. A file
// belongs to one reference key (harness/context/shared_references.hpp: scalar, digits, system,
// parameters) and one executable (a hash of its bytes): only a flow that computes to the bit what it
// answered then is told the answers, so a case gives the same report from the cache as without it
// (tests/check_sharding.sh, mode cache). A file that is not that — unreadable, another key or
// executable, a state of another size — is not used, and the run says so on stderr and computes.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/lagrangian/state.hpp"
#include "core/numerics/scalar.hpp"
#include "harness/context/shared_references.hpp"

namespace vivv {

namespace reference_cache_detail {

template <class T, int N>
nlohmann::json state_json(const State<T, N>& x) {
  nlohmann::json entries = nlohmann::json::array();
  for (Eigen::Index i = 0; i < x.q.size(); ++i) entries.push_back(to_decimal<T>(x.q[i]));
  for (Eigen::Index i = 0; i < x.w.size(); ++i) entries.push_back(to_decimal<T>(x.w[i]));
  return entries;
}

template <class T, int N>
State<T, N> state_from(const nlohmann::json& entries, int n) {
  if (!entries.is_array() || entries.size() != static_cast<std::size_t>(2 * n))
    throw std::runtime_error("a state of " + std::to_string(entries.size()) + " numbers where " +
                             std::to_string(2 * n) + " belong");
  State<T, N> x{zero_vector<T, N>(n), zero_vector<T, N>(n)};
  for (int i = 0; i < n; ++i) {
    x.q[i] = from_decimal<T>(entries[i].get<std::string>());
    x.w[i] = from_decimal<T>(entries[n + i].get<std::string>());
  }
  return x;
}

inline void warn(const std::filesystem::path& file, const std::string& what) {
  std::cerr << "vivv: warning: --reference-cache " << file.string() << ": " << what << "\n";
}

}  // namespace reference_cache_detail

// The answers kept in `key`'s file told to `reference` (which keeps its answers from now on, for
// keep_reference_answers); true if there were any. The cache off: nothing.
template <class Reference>
bool recall_reference_answers(const Reference& reference, const std::string& key, int n) {
  using namespace reference_cache_detail;
  using T = typename Reference::T;
  constexpr int N = Reference::N;
  const std::optional<std::filesystem::path> file = reference_cache_file(key);
  if (!file) return false;
  reference.keep_answers();
  if (!std::filesystem::exists(*file)) return false;
  try {
    std::ifstream in(*file);
    const nlohmann::json kept = nlohmann::json::parse(in);
    if (kept.at("key").get<std::string>() != key || kept.at("executable").get<std::string>() != executable_fingerprint())
      throw std::runtime_error("kept for another reference or another build of vivv");
    const auto answers = [&](const char* field) {
      std::vector<typename Reference::Answer> list;
      for (const nlohmann::json& a : kept.at(field))
        list.push_back({state_from<T, N>(a.at("start"), n), from_decimal<T>(a.at("t").get<std::string>()),
                        state_from<T, N>(a.at("state"), n)});
      return list;
    };
    reference.recall(answers("advanced"), answers("checked"));
    return true;
  } catch (const std::exception& error) {
    warn(*file, std::string("not used (") + error.what() + "); the reference is computed and the file replaced");
    return false;
  }
}

// Writes the answers `reference` kept to `key`'s file: a new file renamed over the old, so that a
// run stopped meanwhile, or another process writing the same key, leaves one whole file.
template <class Reference>
void keep_reference_answers(const Reference& reference, const std::string& key) {
  using namespace reference_cache_detail;
  using T = typename Reference::T;
  constexpr int N = Reference::N;
  const std::optional<std::filesystem::path> file = reference_cache_file(key);
  if (!file) return;
  const auto [advanced, checked] = reference.answers();
  const auto listed = [](const std::vector<typename Reference::Answer>& answers) {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& a : answers)
      list.push_back({{"start", state_json<T, N>(a.start)}, {"t", to_decimal<T>(a.t)}, {"state", state_json<T, N>(a.state)}});
    return list;
  };
  const nlohmann::json kept = {{"format", "vivv-reference-answers/1"},
                               {"key", key},
                               {"executable", executable_fingerprint()},
                               {"advanced", listed(advanced)},
                               {"checked", listed(checked)}};
  const std::filesystem::path written = file->string() + ".new-" + std::to_string(::getpid());
  std::error_code failed;
  {
    std::ofstream out(written);
    out << kept.dump();
    if (!out) failed = std::make_error_code(std::errc::io_error);
  }
  if (!failed) std::filesystem::rename(written, *file, failed);
  if (failed) {
    std::filesystem::remove(written, failed);
    warn(*file, "could not be written; the next run computes the reference again");
  }
}

}  // namespace vivv
