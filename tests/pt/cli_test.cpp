// The path tracer through the pbrkit binary: an interrupted render (SIGINT sent by the
// test mid-render) leaves valid, readable outputs and exits 130; sample-range parts
// merged by 'pbrkit merge' equal a full render.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fcntl.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "pbrkit/image/image_io.h"
#include "pbrkit/pt/film.h"
#include "support/test_paths.h"

namespace pbrkit::test {
namespace {

std::filesystem::path replace_ext(const std::string& path) {
  return std::filesystem::path(path).replace_extension(".exr");
}

TEST(PathTracerCli, InterruptedRenderWritesAValidImageAndExits130) {
  const auto dir = scratch_dir();
  const std::string out = (dir / "x.png").string(), ckpt = (dir / "ckpt.exr").string();
  const std::string cli = cli_path().string();
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    // Child: an effectively endless render; checkpoints tell the parent it has started.
    const int devnull = ::open("/dev/null", O_WRONLY);
    if (devnull >= 0) {
      ::dup2(devnull, 1);
      ::dup2(devnull, 2);
    }
    ::execl(cli.c_str(), cli.c_str(), "render", "cornell", "--renderer", "path", "--width", "32",
            "--height", "24", "--spp", "1000000", "--noise-threshold", "0", "--threads", "1",
            "--checkpoint", ckpt.c_str(), "--checkpoint-interval", "0.05", "-o", out.c_str(),
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  const auto start = std::chrono::steady_clock::now();
  while (!std::filesystem::exists(ckpt) &&
         std::chrono::steady_clock::now() - start < std::chrono::seconds(120))
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_TRUE(std::filesystem::exists(ckpt)) << "the render never started";
  ::kill(pid, SIGINT);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 130);

  const auto layers = read_exr_layers(replace_ext(out));
  ASSERT_FALSE(layers.empty());
  const Image& color = layers.front().second;
  EXPECT_EQ(color.width, 32);
  EXPECT_EQ(color.height, 24);
  double sum = 0.0;
  for (float v : color.data) sum += v;
  EXPECT_GT(sum, 0.0);  // something was rendered
  EXPECT_EQ(read_image(out).width, 32);
  // The final checkpoint holds the same state and can be resumed.
  const Film film = read_film(ckpt);
  EXPECT_GT(film.count[0], 0.0f);
}

TEST(PathTracerCli, MergedSampleRangesEqualTheFullRender) {
  const auto dir = scratch_dir();
  const std::string base = cli_path().string() +
                           " render cornell --renderer path --width 24 --height 16 --spp 8 "
                           "--noise-threshold 0 --float ";
  std::string log;
  ASSERT_EQ(run_command(base + "-o " + (dir / "full.png").string(), &log), 0) << log;
  ASSERT_EQ(run_command(base + "--sample-range 0:3 -o " + (dir / "a.png").string(), &log), 0)
      << log;
  ASSERT_EQ(run_command(base + "--sample-range 3:8 -o " + (dir / "b.png").string(), &log), 0)
      << log;
  ASSERT_EQ(run_command(cli_path().string() + " merge --float " + (dir / "a.exr").string() + " " +
                            (dir / "b.exr").string() + " -o " + (dir / "merged.png").string(),
                        &log),
            0)
      << log;
  const Image full = read_exr_layers(dir / "full.exr").front().second;
  const Image merged = read_exr_layers(dir / "merged.exr").front().second;
  ASSERT_EQ(full.data.size(), merged.data.size());
  for (std::size_t i = 0; i < full.data.size(); ++i)
    ASSERT_NEAR(full.data[i], merged.data[i], 1e-5f * std::max(1.0f, full.data[i]));
  // Bad input: a file that is not an accumulation EXR is refused by name.
  EXPECT_NE(run_command(cli_path().string() + " merge " + (dir / "full.exr").string() + " -o " +
                            (dir / "bad.png").string(),
                        &log),
            0);
  EXPECT_NE(log.find("full.exr"), std::string::npos) << log;
}

}  // namespace
}  // namespace pbrkit::test
