#include "harness/context/shared_references.hpp"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace vivv {

namespace {

struct Kept {
  std::string key;
  std::shared_ptr<const void> reference;
};

struct Registry {
  std::mutex mutex;
  std::set<std::string> wanted;
  std::map<std::string, Kept> kept;  // by typed key
};

Registry& registry() {
  static Registry instance;
  return instance;
}

}  // namespace

std::string reference_key(const CaseSpec& spec) {
  const bool written = spec.source.is_object() && spec.source.contains("system");
  nlohmann::json key = {
      {"scalar", spec.scalar},
      {"digits", spec.scalar == "mpfr" ? spec.digits : 0},
      {"double program", spec.discretization.process_precision == "double"},
      {"system", written ? spec.source["system"] : nlohmann::json(spec.system)},
      {"coordinates", spec.dimension},
      {"parameters", spec.parameters},
  };
  // An L that depends on time has a flow of its own from each initial time.
  if (spec.formula && spec.formula->time_dependent) key["t0"] = spec.start_time;
  return key.dump();
}

void keep_references(const std::set<std::string>& keys) {
  std::map<std::string, Kept> released;  // destroyed outside the lock: a flow's check may be stopping
  {
    Registry& r = registry();
    std::lock_guard<std::mutex> lock(r.mutex);
    r.wanted = keys;
    for (auto it = r.kept.begin(); it != r.kept.end();) {
      if (keys.count(it->second.key)) {
        ++it;
      } else {
        released.insert(r.kept.extract(it++));
      }
    }
  }
}

namespace {

std::optional<std::filesystem::path>& cache_directory() {
  static std::optional<std::filesystem::path> directory;
  return directory;
}

// FNV-1a, 64 bits: a stable hash of bytes (std::hash may differ between builds).
std::uint64_t fnv1a(std::string_view bytes, std::uint64_t hash = 14695981039346656037ull) {
  for (unsigned char c : bytes) hash = (hash ^ c) * 1099511628211ull;
  return hash;
}

std::string hexadecimal(std::uint64_t value) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
  return text;
}

}  // namespace

void set_reference_cache(const std::optional<std::filesystem::path>& directory) { cache_directory() = directory; }

const std::string& executable_fingerprint() {
  static const std::string fingerprint = [] {
    std::ifstream in("/proc/self/exe", std::ios::binary);
    if (!in) throw std::runtime_error("--reference-cache: cannot read this executable (/proc/self/exe) to key the cache by");
    std::uint64_t hash = 14695981039346656037ull;
    std::vector<char> chunk(1 << 16);
    while (in.read(chunk.data(), static_cast<std::streamsize>(chunk.size())) || in.gcount() > 0)
      hash = fnv1a(std::string_view(chunk.data(), static_cast<std::size_t>(in.gcount())), hash);
    return hexadecimal(hash);
  }();
  return fingerprint;
}

std::optional<std::filesystem::path> reference_cache_file(const std::string& key) {
  if (!cache_directory()) return std::nullopt;
  return *cache_directory() / (hexadecimal(fnv1a(executable_fingerprint() + '\n' + key)) + ".json");
}

namespace detail {

std::shared_ptr<const void> kept_reference(const std::string& typed) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  auto it = r.kept.find(typed);
  return it == r.kept.end() ? nullptr : it->second.reference;
}

void keep_reference(const std::string& typed, const std::string& key, std::shared_ptr<const void> made) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  if (r.wanted.count(key)) r.kept[typed] = {key, std::move(made)};
}

}  // namespace detail

}  // namespace vivv
