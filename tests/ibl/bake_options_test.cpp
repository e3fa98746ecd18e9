// BakeOptions validation: the library names the BakeOptions field it rejects, never a
// command-line flag (the CLI's flag names are checked in tests/cli/bake_cli_test.cpp).
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "pbrkit/ibl/bake.h"
#include "pbrkit/util/error.h"

namespace pbrkit {
namespace {

// The message check_bake_options() throws for `options`, or "" if it accepts them.
std::string check_message(const BakeOptions& options) {
  try {
    check_bake_options(options);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

struct BadField {
  std::function<void(BakeOptions&)> set;
  int BakeOptions::*field;
  const char* expected;  // the whole message, written out
};

TEST(BakeOptions, DefaultsAndLimitsAreAccepted) {
  EXPECT_FALSE(find_bake_options_problem(BakeOptions{}).has_value());
  EXPECT_EQ(check_message(BakeOptions{}), "");
  BakeOptions largest;
  largest.face_size = 4096;
  largest.min_face_size = 4096;
  largest.samples = 1048576;
  largest.irradiance_size = 1024;
  largest.lut_size = 4096;
  EXPECT_EQ(check_message(largest), "");
  BakeOptions smallest;
  smallest.face_size = 1;
  smallest.min_face_size = 1;
  smallest.samples = 1;
  smallest.irradiance_size = 1;
  smallest.lut_size = 1;
  EXPECT_EQ(check_message(smallest), "");
}

TEST(BakeOptions, EachRejectedValueNamesItsFieldAndNoFlag) {
  const BadField cases[] = {
      {[](BakeOptions& o) { o.face_size = 100; }, &BakeOptions::face_size,
       "BakeOptions::face_size must be a power of two in 1..4096, got 100"},
      {[](BakeOptions& o) { o.face_size = 8192; }, &BakeOptions::face_size,
       "BakeOptions::face_size must be a power of two in 1..4096, got 8192"},
      {[](BakeOptions& o) { o.face_size = 0; }, &BakeOptions::face_size,
       "BakeOptions::face_size must be a power of two in 1..4096, got 0"},
      {[](BakeOptions& o) { o.min_face_size = 3; }, &BakeOptions::min_face_size,
       "BakeOptions::min_face_size must be a power of two in 1..256 (the face size), got 3"},
      {[](BakeOptions& o) {
         o.face_size = 16;
         o.min_face_size = 32;
       },
       &BakeOptions::min_face_size,
       "BakeOptions::min_face_size must be a power of two in 1..16 (the face size), got 32"},
      {[](BakeOptions& o) { o.samples = 0; }, &BakeOptions::samples,
       "BakeOptions::samples must be in 1..1048576, got 0"},
      {[](BakeOptions& o) { o.samples = 1048577; }, &BakeOptions::samples,
       "BakeOptions::samples must be in 1..1048576, got 1048577"},
      {[](BakeOptions& o) { o.irradiance_size = 1025; }, &BakeOptions::irradiance_size,
       "BakeOptions::irradiance_size must be in 1..1024, got 1025"},
      {[](BakeOptions& o) { o.lut_size = -1; }, &BakeOptions::lut_size,
       "BakeOptions::lut_size must be in 1..4096, got -1"},
  };
  for (const BadField& c : cases) {
    BakeOptions options;
    c.set(options);
    const std::string message = check_message(options);
    EXPECT_EQ(message, c.expected);
    EXPECT_EQ(message.find("--"), std::string::npos) << message;
    const auto problem = find_bake_options_problem(options);
    ASSERT_TRUE(problem.has_value()) << c.expected;
    EXPECT_TRUE(problem->field == c.field) << c.expected;
    // The problem alone carries neither the field's nor a flag's name, so a caller can
    // prefix its own.
    EXPECT_EQ(problem->message.find("BakeOptions"), std::string::npos) << problem->message;
    EXPECT_EQ(problem->message.find("--"), std::string::npos) << problem->message;
  }
}

TEST(BakeOptions, TheFirstBadFieldIsReported) {
  BakeOptions options;
  options.samples = 0;
  options.lut_size = 0;
  const auto problem = find_bake_options_problem(options);
  ASSERT_TRUE(problem.has_value());
  EXPECT_TRUE(problem->field == &BakeOptions::samples);
  EXPECT_EQ(problem->name, "samples");
}

TEST(BakeOptions, BakeEnvironmentRejectsBadOptionsBeforeBaking) {
  BakeOptions options;
  options.irradiance_size = 0;
  try {
    bake_environment(Environment::constant(glm::vec3(1.0f)), options);
    FAIL() << "bake_environment accepted irradiance_size = 0";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "BakeOptions::irradiance_size must be in 1..1024, got 0");
  }
}

}  // namespace
}  // namespace pbrkit
