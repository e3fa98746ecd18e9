// The memory a process may still allocate: MemAvailable, or less where a cgroup (v2 or v1)
// of the process or of any ancestor has a limit; read from fake cgroup trees written here.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "pbrkit/util/available_memory.h"

namespace pbrkit {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kMiB = std::size_t(1) << 20;
constexpr std::size_t kMemAvailable = 16384 * kMiB;

// A scratch cgroup mount, removed at the end of the test.
struct FakeCgroups {
  fs::path root =
      fs::temp_directory_path() / ("pbrkit-cgroups-" + std::to_string(::getpid()) + "-" +
                                   ::testing::UnitTest::GetInstance()->current_test_info()->name());
  FakeCgroups() { fs::create_directories(root); }
  ~FakeCgroups() {
    std::error_code ec;
    fs::remove_all(root, ec);
  }
  void write(const fs::path& file, const std::string& text) const {
    fs::create_directories((root / file).parent_path());
    std::ofstream(root / file) << text;
  }
};

TEST(AvailableMemory, WithoutCgroupLimitsIsMemAvailable) {
  FakeCgroups c;
  c.write("memory.max", "max\n");                                    // v2, unlimited
  c.write("memory/memory.limit_in_bytes", "9223372036854771712\n");  // v1, unlimited
  EXPECT_EQ(available_memory("0::/\n", c.root, kMemAvailable), kMemAvailable);
  EXPECT_EQ(available_memory("4:memory:/\n", c.root, kMemAvailable), kMemAvailable);
  EXPECT_EQ(available_memory("", c.root, kMemAvailable), kMemAvailable);
  EXPECT_EQ(available_memory("garbage\n0::\n", c.root / "missing", kMemAvailable), kMemAvailable);
}

TEST(AvailableMemory, CgroupV2TakesTheLeastHeadroomOfTheCgroupAndItsAncestors) {
  FakeCgroups c;
  // A Slurm-like tree: the job limited to 1 GiB with 256 MiB in use, of which 64 MiB is
  // inactive page cache; the step below it unlimited.
  c.write("system.slice/job_7/memory.max", std::to_string(1024 * kMiB));
  c.write("system.slice/job_7/memory.current", std::to_string(256 * kMiB));
  c.write("system.slice/job_7/memory.stat",
          "anon 100\ninactive_file " + std::to_string(64 * kMiB) + "\nactive_file 5\n");
  c.write("system.slice/job_7/step_0/memory.max", "max\n");
  c.write("system.slice/job_7/step_0/memory.current", std::to_string(200 * kMiB));
  EXPECT_EQ(available_memory("0::/system.slice/job_7/step_0\n", c.root, kMemAvailable),
            (1024 - 256 + 64) * kMiB);
  // MemAvailable when it is the smaller.
  EXPECT_EQ(available_memory("0::/system.slice/job_7/step_0\n", c.root, 100 * kMiB), 100 * kMiB);
  // A cgroup over its limit leaves nothing.
  c.write("system.slice/job_7/step_0/memory.max", std::to_string(150 * kMiB));
  EXPECT_EQ(available_memory("0::/system.slice/job_7/step_0\n", c.root, kMemAvailable), 0u);
}

TEST(AvailableMemory, CgroupV1ReadsTheMemoryHierarchy) {
  FakeCgroups c;
  c.write("memory/memory.limit_in_bytes", "9223372036854771712\n");
  c.write("memory/slurm/uid_0/job_9/memory.limit_in_bytes", std::to_string(2048 * kMiB));
  c.write("memory/slurm/uid_0/job_9/memory.usage_in_bytes", std::to_string(512 * kMiB));
  c.write("memory/slurm/uid_0/job_9/memory.stat",
          "cache 1\ntotal_inactive_file " + std::to_string(128 * kMiB) + "\n");
  c.write("memory/slurm/uid_0/job_9/step_0/memory.limit_in_bytes", "9223372036854771712\n");
  const std::string self = "9:pids:/\n4:memory:/slurm/uid_0/job_9/step_0\n1:cpu,cpuacct:/\n";
  EXPECT_EQ(available_memory(self, c.root, kMemAvailable), (2048 - 512 + 128) * kMiB);
  // A container: the path names the host's hierarchy, not mounted here; the mount's root is
  // the container's cgroup.
  FakeCgroups container;
  container.write("memory/memory.limit_in_bytes", std::to_string(3072 * kMiB));
  container.write("memory/memory.usage_in_bytes", std::to_string(1024 * kMiB));
  EXPECT_EQ(available_memory("4:memory:/docker/0123abcd\n", container.root, kMemAvailable),
            2048 * kMiB);
}

}  // namespace
}  // namespace pbrkit
