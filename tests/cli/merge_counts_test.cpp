// `pbrkit merge` keeps the parts' counts of what their renders could not represent (samples
// whose radiance was not finite, paths deeper than the medium stack): it sums them, warns,
// and writes the sums into the merged EXRs' headers.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "pbrkit/image/image_io.h"
#include "pbrkit/pt/film.h"
#include "support/test_paths.h"

namespace pbrkit {
namespace {

TEST(MergeCounts, PartsCountsAreSummedWarnedAndWritten) {
  const std::filesystem::path dir = test::scratch_dir();
  for (int k = 0; k < 2; ++k) {
    Film part(4, 4);
    for (float& c : part.count) c = 2.0f;
    part.sample_begin = std::uint32_t(2 * k);
    part.non_finite_samples = std::uint64_t(3 + k);  // 3 and 4
    part.medium_overflows = std::uint64_t(10 * k);   // 0 and 10
    write_film(dir / ("part" + std::to_string(k) + ".exr"), part);
  }
  std::string log;
  const int code =
      test::run_command(test::cli_path().string() + " merge " + (dir / "part0.exr").string() + " " +
                            (dir / "part1.exr").string() + " -o " + (dir / "merged.exr").string() +
                            " --accumulation " + (dir / "merged_accumulation.exr").string(),
                        &log);
  ASSERT_EQ(code, 0) << log;
  EXPECT_NE(log.find("7 samples whose radiance was not finite"), std::string::npos) << log;
  EXPECT_NE(log.find("10 paths inside more than 8 nested volumes"), std::string::npos) << log;
  ExrAttributes attributes;
  read_exr_layers(dir / "merged.exr", &attributes);
  EXPECT_EQ(attributes[kNonFiniteSamplesAttribute], "7");
  EXPECT_EQ(attributes[kMediumOverflowsAttribute], "10");
  const Film merged = read_film(dir / "merged_accumulation.exr");
  EXPECT_EQ(merged.non_finite_samples, 7u);
  EXPECT_EQ(merged.medium_overflows, 10u);
}

}  // namespace
}  // namespace pbrkit
