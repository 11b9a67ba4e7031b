// How much memory this process may still take: the least of the machine's physical memory, the
// address-space and data limits it runs under (RLIMIT_AS, RLIMIT_DATA: ulimit -v, -d) less what it
// has already mapped, and its cgroup's memory.max (v2) or memory.limit_in_bytes (v1) less the
// cgroup's present use. A batch system or a container sets the last two; the physical memory alone
// once let a run estimated to fit end in a bare std::bad_alloc.
#pragma once

#include <sys/resource.h>
#include <unistd.h>

#include <fstream>
#include <limits>
#include <sstream>
#include <string>

namespace vivv {

struct MemoryLimit {
  double bytes = std::numeric_limits<double>::infinity();  // infinity: no limit could be read
  std::string what;  // which limit it is, for a message: "this machine's physical memory"
};

namespace memory_limit_detail {

// A number in the first line of `path` ("max" or no file: none).
inline double read_bytes(const std::string& path) {
  std::ifstream in(path);
  std::string text;
  if (!(in >> text) || text == "max") return std::numeric_limits<double>::infinity();
  try {
    return std::stod(text);
  } catch (const std::exception&) {
    return std::numeric_limits<double>::infinity();
  }
}

// The cgroup (v2: "0::/path"; v1: the memory controller's line) this process is in.
inline std::string cgroup_path(bool v2) {
  std::ifstream in("/proc/self/cgroup");
  std::string line;
  while (std::getline(in, line)) {
    const auto first = line.find(':'), second = line.find(':', first + 1);
    if (first == std::string::npos || second == std::string::npos) continue;
    const std::string controllers = line.substr(first + 1, second - first - 1);
    if (v2 ? controllers.empty() : controllers.find("memory") != std::string::npos) return line.substr(second + 1);
  }
  return "";
}

// The bytes this process has mapped (VmSize in /proc/self/status).
inline double mapped_bytes() {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmSize:", 0) == 0) {
      std::istringstream fields(line.substr(7));
      double kib = 0;
      fields >> kib;
      return kib * 1024;
    }
  return 0;
}

}  // namespace memory_limit_detail

inline MemoryLimit memory_limit() {
  using namespace memory_limit_detail;
  MemoryLimit limit;
  const auto known = [](double bytes) { return bytes < std::numeric_limits<double>::infinity() ? bytes : 0.0; };
  const auto consider = [&limit](double bytes, const std::string& what) {
    if (bytes < limit.bytes) limit.bytes = bytes < 0 ? 0 : bytes, limit.what = what;
  };
  const double pages = static_cast<double>(sysconf(_SC_PHYS_PAGES)), page = static_cast<double>(sysconf(_SC_PAGE_SIZE));
  if (pages > 0 && page > 0) consider(pages * page, "this machine's physical memory");
  struct rlimit address_space {}, data {};
  if (getrlimit(RLIMIT_AS, &address_space) == 0 && address_space.rlim_cur != RLIM_INFINITY)
    consider(static_cast<double>(address_space.rlim_cur) - mapped_bytes(),
             "what its address-space limit, RLIMIT_AS or ulimit -v, leaves");
  if (getrlimit(RLIMIT_DATA, &data) == 0 && data.rlim_cur != RLIM_INFINITY)
    consider(static_cast<double>(data.rlim_cur), "its data-segment limit, RLIMIT_DATA or ulimit -d");
  // v2 (or the unified hierarchy of a hybrid one), then v1's memory controller: each that exists.
  const std::string unified = cgroup_path(true), memory = cgroup_path(false);
  for (const std::string& directory : {"/sys/fs/cgroup" + unified, "/sys/fs/cgroup/unified" + unified}) {
    if (unified.empty()) break;
    const double maximum = read_bytes(directory + "/memory.max");
    if (maximum < std::numeric_limits<double>::infinity())
      consider(maximum - known(read_bytes(directory + "/memory.current")),
               "what its cgroup's memory.max leaves");
  }
  if (!memory.empty()) {
    const std::string directory = "/sys/fs/cgroup/memory" + memory;
    const double maximum = read_bytes(directory + "/memory.limit_in_bytes");
    if (maximum < 1e18)  // v1 writes "no limit" as a number near 2^63
      consider(maximum - known(read_bytes(directory + "/memory.usage_in_bytes")),
               "what its cgroup's memory.limit_in_bytes leaves");
  }
  return limit;
}

}  // namespace vivv
