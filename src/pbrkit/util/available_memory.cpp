#include "pbrkit/util/available_memory.h"

#include <algorithm>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>

namespace pbrkit {

namespace {

namespace fs = std::filesystem;

// A file holding one number; nothing for a missing file, "max" (cgroup v2's no limit) or
// anything else that is not a number.
std::optional<std::size_t> read_number(const fs::path& file) {
  std::ifstream in(file);
  unsigned long long value = 0;
  if (!(in >> value)) return std::nullopt;
  return std::size_t(value);
}

// A key's value in a memory.stat file (lines "key value"); 0 when absent.
std::size_t stat_value(const fs::path& file, const std::string& key) {
  std::ifstream in(file);
  std::string name;
  unsigned long long value = 0;
  while (in >> name >> value)
    if (name == key) return std::size_t(value);
  return 0;
}

// cgroup v1 reports "no limit" as the largest page-aligned 63-bit value; anything from 2^62
// up is no limit on any machine.
constexpr std::size_t kNoLimit = std::size_t(1) << 62;

// The least headroom of `dir` and its ancestors up to `base` (the hierarchy's root), with the
// given files' names; `available` when none is limited.
std::size_t least_headroom(fs::path dir, const fs::path& base, const char* limit_file,
                           const char* usage_file, const char* inactive_key,
                           std::size_t available) {
  std::error_code ec;
  // Inside a container the path names the host's hierarchy, which is not mounted: the
  // container's own cgroup is then the mount's root.
  if (!fs::is_directory(dir, ec)) dir = base;
  for (;;) {
    const std::optional<std::size_t> limit = read_number(dir / limit_file);
    if (limit && *limit < kNoLimit) {
      const std::size_t usage = read_number(dir / usage_file).value_or(0);
      const std::size_t inactive = stat_value(dir / "memory.stat", inactive_key);
      const std::size_t used = usage - std::min(usage, inactive);
      available = std::min(available, *limit > used ? *limit - used : 0);
    }
    if (dir == base || !dir.has_parent_path() || dir.parent_path() == dir) break;
    dir = dir.parent_path();
  }
  return available;
}

}  // namespace

std::size_t available_memory(const std::string& proc_self_cgroup, const fs::path& cgroup_root,
                             std::size_t mem_available) {
  std::size_t available = mem_available;
  std::istringstream lines(proc_self_cgroup);
  std::string line;
  while (std::getline(lines, line)) {
    const std::size_t a = line.find(':');
    const std::size_t b = a == std::string::npos ? a : line.find(':', a + 1);
    if (b == std::string::npos) continue;
    const std::string controllers = line.substr(a + 1, b - a - 1);
    const fs::path path = fs::path(line.substr(b + 1)).relative_path();
    if (line.compare(0, a, "0") == 0 && controllers.empty()) {
      available = least_headroom(cgroup_root / path, cgroup_root, "memory.max", "memory.current",
                                 "inactive_file", available);
    } else {
      std::istringstream names(controllers);
      std::string name;
      while (std::getline(names, name, ','))
        if (name == "memory") {
          const fs::path base = cgroup_root / "memory";
          available = least_headroom(base / path, base, "memory.limit_in_bytes",
                                     "memory.usage_in_bytes", "total_inactive_file", available);
        }
    }
  }
  return available;
}

std::size_t available_memory() {
  std::size_t mem_available = std::numeric_limits<std::size_t>::max();
  std::ifstream meminfo("/proc/meminfo");
  std::string key, unit;
  unsigned long long kb = 0;
  while (meminfo >> key >> kb >> unit)
    if (key == "MemAvailable:") {
      mem_available = std::size_t(kb) * 1024;
      break;
    }
  std::ifstream cgroup_file("/proc/self/cgroup");
  std::stringstream text;
  text << cgroup_file.rdbuf();
  return available_memory(text.str(), "/sys/fs/cgroup", mem_available);
}

}  // namespace pbrkit
