// `pbrkit brdf`: the CSV tables agree with the closed forms at a few points, the albedo
// curves behave as Kulla-Conty promises, and the PNGs are real PNG images.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include "pbrkit/image/image_io.h"
#include "support/test_paths.h"

namespace pbrkit {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = 3.14159265358979323846;

struct Csv {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
  int col(const std::string& name) const {
    for (std::size_t i = 0; i < columns.size(); ++i)
      if (columns[i] == name) return int(i);
    ADD_FAILURE() << "no column " << name;
    return 0;
  }
  // The row whose first column is closest to x.
  const std::vector<double>& at(double x) const {
    std::size_t best = 0;
    for (std::size_t i = 0; i < rows.size(); ++i)
      if (std::abs(rows[i][0] - x) < std::abs(rows[best][0] - x)) best = i;
    return rows[best];
  }
};

Csv read_csv(const fs::path& p) {
  Csv csv;
  std::ifstream in(p);
  EXPECT_TRUE(in) << p;
  std::string line;
  std::getline(in, line);
  std::stringstream header(line);
  for (std::string c; std::getline(header, c, ',');) csv.columns.push_back(c);
  while (std::getline(in, line)) {
    std::stringstream ls(line);
    std::vector<double> row;
    for (std::string c; std::getline(ls, c, ',');) row.push_back(std::stod(c));
    EXPECT_EQ(row.size(), csv.columns.size());
    csv.rows.push_back(row);
  }
  return csv;
}

class BrdfCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ =
        new fs::path(fs::temp_directory_path() / ("pbrkit-brdf-cli-" + std::to_string(::getpid())));
    fs::remove_all(*dir_);
    std::string out;
    status_ = test::run_command(test::cli_path().string() + " brdf -o " + dir_->string(), &out);
    output_ = new std::string(out);
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
    delete output_;
  }
  static fs::path* dir_;
  static std::string* output_;
  static int status_;
};
fs::path* BrdfCli::dir_ = nullptr;
std::string* BrdfCli::output_ = nullptr;
int BrdfCli::status_ = -1;

TEST_F(BrdfCli, Succeeds) {
  ASSERT_EQ(status_, 0) << *output_;
}

TEST_F(BrdfCli, NdfMatchesClosedForm) {
  const Csv csv = read_csv(*dir_ / "brdf_D.csv");
  ASSERT_EQ(csv.columns.size(), 6u);
  for (double alpha : {0.1, 0.25, 0.5, 0.75, 1.0}) {
    char name[32];
    std::snprintf(name, sizeof name, "alpha=%g", alpha);
    const int c = csv.col(name);
    for (double nh : {0.01, 0.5, 0.9, 1.0}) {  // (n.h = 0 is the chi+ boundary: D = 0 there)
      const auto& row = csv.at(nh);
      const double x = row[0];
      const double a2 = alpha * alpha;
      const double want = a2 / (kPi * std::pow(x * x * (a2 - 1) + 1, 2));
      EXPECT_NEAR(row[c], want, 1e-5 * std::max(1.0, want)) << name << " n.h=" << x;
    }
  }
  // The peak at alpha = 0.1 is 1/(pi alpha^2) = 31.83: a density, not a probability.
  EXPECT_NEAR(csv.at(1.0)[csv.col("alpha=0.1")], 1.0 / (kPi * 0.01), 1e-3);
  // D(h)(n.h) integrates to 1 over the hemisphere: 2 pi int D(mu) mu dmu (trapezoid rule).
  for (const char* name : {"alpha=0.25", "alpha=0.5", "alpha=1"}) {
    const int c = csv.col(name);
    double integral = 0.0;
    for (std::size_t i = 1; i < csv.rows.size(); ++i) {
      const auto &p = csv.rows[i - 1], &q = csv.rows[i];
      integral += 0.5 * (p[c] * p[0] + q[c] * q[0]) * (q[0] - p[0]);
    }
    EXPECT_NEAR(2 * kPi * integral, 1.0, 0.01) << name;
  }
}

TEST_F(BrdfCli, G1MatchesClosedForms) {
  const Csv csv = read_csv(*dir_ / "brdf_G1.csv");
  for (double r : {0.25, 0.5, 1.0}) {
    char direct[48], ibl[48], smith[48];
    std::snprintf(direct, sizeof direct, "r=%g Schlick k_direct", r);
    std::snprintf(ibl, sizeof ibl, "r=%g Schlick k_IBL", r);
    std::snprintf(smith, sizeof smith, "r=%g Smith exact", r);
    for (double nv : {0.05, 0.3, 0.7, 1.0}) {
      const auto& row = csv.at(nv);
      const double mu = row[0];
      const double kd = (r + 1) * (r + 1) / 8, ki = r * r / 2, a = r * r;
      EXPECT_NEAR(row[csv.col(direct)], mu / (mu * (1 - kd) + kd), 1e-5);
      EXPECT_NEAR(row[csv.col(ibl)], mu / (mu * (1 - ki) + ki), 1e-5);
      // Smith G1 for GGX: 2 / (1 + sqrt(1 + alpha^2 tan^2 theta)).
      const double tan2 = (1 - mu * mu) / (mu * mu);
      EXPECT_NEAR(row[csv.col(smith)], 2 / (1 + std::sqrt(1 + a * a * tan2)), 1e-5);
    }
    // Masking falls towards grazing.
    EXPECT_LT(csv.rows.front()[csv.col(smith)], csv.rows.back()[csv.col(smith)]);
  }
}

TEST_F(BrdfCli, FresnelMatchesSchlick) {
  const Csv csv = read_csv(*dir_ / "brdf_fresnel.csv");
  ASSERT_EQ(csv.columns.size(), 11u);
  auto lum = [](double r, double g, double b) { return 0.2126 * r + 0.7152 * g + 0.0722 * b; };
  struct M {
    const char* name;
    double r, g, b;
  };
  for (const M& m : {M{"water", 0.02, 0.02, 0.02}, M{"diamond", 0.17, 0.17, 0.17},
                     M{"gold", 1.0, 0.71, 0.29}, M{"copper", 0.95, 0.64, 0.54}}) {
    const int c = csv.col(m.name);
    for (double vh : {0.0, 0.25, 0.5, 1.0}) {
      const auto& row = csv.at(vh);
      const double w = std::pow(1 - row[0], 5);
      const double want = lum(m.r + (1 - m.r) * w, m.g + (1 - m.g) * w, m.b + (1 - m.b) * w);
      EXPECT_NEAR(row[c], want, 1e-5) << m.name << " v.h=" << row[0];
    }
    EXPECT_NEAR(csv.at(0.0)[c], 1.0, 1e-6);  // grazing: F = 1
  }
}

TEST_F(BrdfCli, AlbedoShowsEnergyLossAndCompensation) {
  const Csv csv = read_csv(*dir_ / "brdf_albedo.csv");
  for (double r : {0.25, 0.5, 0.75, 1.0}) {
    char single[32], multi[32], table[32];
    std::snprintf(single, sizeof single, "r=%g single", r);
    std::snprintf(multi, sizeof multi, "r=%g multiscatter", r);
    std::snprintf(table, sizeof table, "r=%g table", r);
    for (const auto& row : csv.rows) {
      if (row[0] < 0.2) continue;  // grazing: fewer effective samples
      // Kulla-Conty: a white metal reflects everything (furnace test), to sampling noise.
      EXPECT_NEAR(row[csv.col(multi)], 1.0, 0.02) << multi << " mu=" << row[0];
      // Single scattering never gains energy and matches the tabulated E(mu).
      EXPECT_LE(row[csv.col(single)], 1.0 + 0.01) << single;
      EXPECT_NEAR(row[csv.col(single)], row[csv.col(table)], 0.02) << single << " mu=" << row[0];
    }
  }
  // Energy loss grows with roughness (at normal incidence).
  const auto& top = csv.at(1.0);
  EXPECT_GT(top[csv.col("r=0.25 single")], top[csv.col("r=0.5 single")]);
  EXPECT_GT(top[csv.col("r=0.5 single")], top[csv.col("r=1 single")] + 0.1);
}

TEST_F(BrdfCli, WritesValidPngPlots) {
  for (const char* name : {"brdf_D.png", "brdf_G1.png", "brdf_fresnel.png", "brdf_albedo.png"}) {
    const fs::path p = *dir_ / name;
    ASSERT_TRUE(fs::exists(p)) << p;
    EXPECT_GT(fs::file_size(p), 10000u) << p;  // a plot, not an empty canvas
    std::ifstream in(p, std::ios::binary);
    char magic[8] = {};
    in.read(magic, 8);
    EXPECT_EQ(std::string(magic, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << p;
    const Image img = read_image(p);
    EXPECT_EQ(img.width, 1100) << p;
    EXPECT_EQ(img.height, 650) << p;
  }
  // No temporary files are left behind.
  for (const auto& e : fs::directory_iterator(*dir_))
    EXPECT_NE(e.path().filename().string()[0], '.') << e.path();
}

TEST(BrdfCliNoGnuplot, WritesCsvAndFailsClearly) {
  const fs::path dir = test::scratch_dir();
  std::string out;
  const int status = test::run_command(
      "PATH=/nonexistent " + test::cli_path().string() + " brdf -o " + dir.string(), &out);
  EXPECT_NE(status, 0) << out;
  EXPECT_NE(out.find("gnuplot"), std::string::npos) << out;
  EXPECT_TRUE(fs::exists(dir / "brdf_D.csv"));
  EXPECT_TRUE(fs::exists(dir / "brdf_albedo.csv"));
  EXPECT_FALSE(fs::exists(dir / "brdf_D.png"));
}

}  // namespace
}  // namespace pbrkit
