#include "brdf_plots.h"

#include <fmt/format.h>

#include <cmath>

#include "pbrkit/core/brdf.h"
#include "pbrkit/core/color.h"
#include "pbrkit/core/energy.h"
#include "pbrkit/core/microfacet.h"
#include "pbrkit/core/sampling.h"

namespace pbrkit::cli {

std::string PlotTable::to_csv() const {
  std::string out;
  for (std::size_t j = 0; j < columns.size(); ++j) out += (j ? "," : "") + columns[j];
  out += '\n';
  for (const auto& row : rows) {
    for (std::size_t j = 0; j < row.size(); ++j) {
      if (j) out += ',';
      out += fmt::format("{:.9g}", row[j]);
    }
    out += '\n';
  }
  return out;
}

std::vector<float> ndf_plot_alphas() {
  return {0.1f, 0.25f, 0.5f, 0.75f, 1.0f};
}
std::vector<float> g1_plot_roughnesses() {
  return {0.25f, 0.5f, 1.0f};
}
std::vector<float> albedo_plot_roughnesses() {
  return {0.1f, 0.25f, 0.5f, 0.75f, 1.0f};
}

PlotTable ndf_plot_table(int points) {
  PlotTable t;
  t.columns.push_back("n.h");
  for (float a : ndf_plot_alphas()) t.columns.push_back(fmt::format("alpha={:g}", a));
  for (int i = 0; i < points; ++i) {
    const float NdotH = float(i) / float(points - 1);
    std::vector<double> row{NdotH};
    for (float a : ndf_plot_alphas()) row.push_back(DistributionGGX(NdotH, a));
    t.rows.push_back(std::move(row));
  }
  return t;
}

PlotTable g1_plot_table(int points) {
  PlotTable t;
  t.columns.push_back("n.v");
  for (float r : g1_plot_roughnesses()) {
    t.columns.push_back(fmt::format("r={:g} Schlick k_direct", r));
    t.columns.push_back(fmt::format("r={:g} Schlick k_IBL", r));
    t.columns.push_back(fmt::format("r={:g} Smith exact", r));
  }
  for (int i = 1; i <= points; ++i) {
    const float NdotV = float(i) / float(points);
    const glm::vec3 v(std::sqrt(std::max(0.0f, 1.0f - NdotV * NdotV)), 0.0f, NdotV);
    std::vector<double> row{NdotV};
    for (float r : g1_plot_roughnesses()) {
      row.push_back(GeometrySchlickGGX(NdotV, k_direct(r)));
      row.push_back(GeometrySchlickGGX(NdotV, k_ibl(r)));
      row.push_back(SmithG1GGX(v, r * r));
    }
    t.rows.push_back(std::move(row));
  }
  return t;
}

const std::vector<FresnelMaterial>& fresnel_materials() {
  // LearnOpenGL's table of F0 (linear), dielectrics as grey values.
  static const std::vector<FresnelMaterial> kTable = {
      {"water", glm::vec3(0.02f)},
      {"plastic/glass (low)", glm::vec3(0.03f)},
      {"plastic (high)", glm::vec3(0.05f)},
      {"glass (high)/ruby", glm::vec3(0.08f)},
      {"diamond", glm::vec3(0.17f)},
      {"iron", glm::vec3(0.56f, 0.57f, 0.58f)},
      {"copper", glm::vec3(0.95f, 0.64f, 0.54f)},
      {"gold", glm::vec3(1.00f, 0.71f, 0.29f)},
      {"aluminium", glm::vec3(0.91f, 0.92f, 0.92f)},
      {"silver", glm::vec3(0.95f, 0.93f, 0.88f)},
  };
  return kTable;
}

PlotTable fresnel_plot_table(int points) {
  PlotTable t;
  t.columns.push_back("v.h");
  for (const auto& m : fresnel_materials()) t.columns.push_back(m.name);
  for (int i = 0; i < points; ++i) {
    const float VdotH = float(i) / float(points - 1);
    std::vector<double> row{VdotH};
    for (const auto& m : fresnel_materials()) row.push_back(luminance(fresnelSchlick(VdotH, m.F0)));
    t.rows.push_back(std::move(row));
  }
  return t;
}

namespace {

// E(mu) = int f cos dwi, estimated as the mean of Brdf::sample's weights f cos / pdf (an
// unbiased estimator whatever lobe the sample came from).
double integrate_albedo(const Brdf& brdf, float mu, std::uint32_t stream, int samples) {
  const OwenSobolSampler sampler(0x5eed);
  const glm::vec3 wo(std::sqrt(std::max(0.0f, 1.0f - mu * mu)), 0.0f, mu);
  double sum = 0.0;
  for (int i = 0; i < samples; ++i) {
    const auto index = static_cast<std::uint32_t>(i);
    const BrdfSample s =
        brdf.sample(wo, sampler.sample(stream, index, 0), sampler.sample_2d(stream, index, 1));
    if (s.valid) sum += s.weight.g;
  }
  return sum / samples;
}

}  // namespace

PlotTable albedo_plot_table(int mu_points, int samples) {
  PlotTable t;
  t.columns.push_back("mu");
  for (float r : albedo_plot_roughnesses()) {
    t.columns.push_back(fmt::format("r={:g} single", r));
    t.columns.push_back(fmt::format("r={:g} multiscatter", r));
    t.columns.push_back(fmt::format("r={:g} table", r));
  }
  BrdfOptions single, multi;
  single.model = multi.model = BrdfModel::kReference;
  single.multiscatter = false;
  multi.multiscatter = true;
  const EnergyTable& table = EnergyTable::get(direct_geometry(BrdfModel::kReference));
  for (int i = 0; i < mu_points; ++i) {
    const float mu = 0.02f + 0.98f * float(i) / float(mu_points - 1);
    std::vector<double> row{mu};
    std::uint32_t stream = static_cast<std::uint32_t>(i) * 16u;
    for (float r : albedo_plot_roughnesses()) {
      const Brdf a(glm::vec3(1.0f), 1.0f, r, single);
      const Brdf b(glm::vec3(1.0f), 1.0f, r, multi);
      row.push_back(integrate_albedo(a, mu, stream++, samples));
      row.push_back(integrate_albedo(b, mu, stream++, samples));
      row.push_back(table.E(mu, r));
    }
    t.rows.push_back(std::move(row));
  }
  return t;
}

}  // namespace pbrkit::cli
