#pragma once
// How much more memory this process may allocate before it is killed: what decides whether
// a scene is built or refused with the figures (pt/geometry.h).
#include <cstddef>
#include <filesystem>
#include <string>

namespace pbrkit {

/// Bytes this process can still allocate: /proc/meminfo's MemAvailable, and where the
/// process runs in a memory-limited control group (a container, a Slurm job's step), the
/// least headroom of its cgroup and every ancestor's (the kernel kills when any of them is
/// over its limit), read from cgroup v2 (memory.max, memory.current) or v1
/// (memory.limit_in_bytes, memory.usage_in_bytes). A cgroup's usage counts its page cache;
/// the inactive file pages (memory.stat), which the kernel reclaims before it kills, are not
/// counted against the headroom.
std::size_t available_memory();

/// The same from given sources: `proc_self_cgroup`, the text of /proc/self/cgroup
/// ("id:controllers:path" lines); `cgroup_root`, where the cgroup filesystems are mounted
/// (/sys/fs/cgroup: cgroup v2 there, v1 in its `memory` directory); `mem_available`, bytes.
std::size_t available_memory(const std::string& proc_self_cgroup,
                             const std::filesystem::path& cgroup_root, std::size_t mem_available);

}  // namespace pbrkit
