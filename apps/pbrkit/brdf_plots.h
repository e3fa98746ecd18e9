#pragma once
// The data behind `pbrkit brdf`: LearnOpenGL's curves (GGX D, Smith/Schlick-GGX G1, Schlick
// Fresnel for a table of F0, and the directional albedo of a white metal with and without
// multiple-scattering compensation), tabulated from the library's own BRDF code so the
// plots show exactly what the renderers evaluate.
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace pbrkit::cli {

/// A table of curves: column 0 is the abscissa, each further column one curve.
struct PlotTable {
  std::vector<std::string> columns;       ///< header names (no commas)
  std::vector<std::vector<double>> rows;  ///< rows[i][j]: value of column j at point i
  /// CSV text: one header line, then one line per row (%.9g numbers).
  std::string to_csv() const;
};

/// Alpha values of the D plot and roughness values of the G1 and albedo plots.
std::vector<float> ndf_plot_alphas();          ///< {0.1, 0.25, 0.5, 0.75, 1.0}
std::vector<float> g1_plot_roughnesses();      ///< {0.25, 0.5, 1.0}
std::vector<float> albedo_plot_roughnesses();  ///< {0.1, 0.25, 0.5, 0.75, 1.0}

/// D(n.h) = DistributionGGX for each alpha; n.h from 0 to 1 in `points` steps.
/// Columns: "n.h", "alpha=0.1", ...
PlotTable ndf_plot_table(int points = 201);

/// G1(n.v) for each roughness r (alpha = r^2), three forms per r: Schlick-GGX with
/// k_direct(r), with k_ibl(r), and Smith's exact G1 for GGX. n.v from 1/points to 1.
/// Columns: "n.v", then per r "r=0.25 Schlick k_direct", "r=0.25 Schlick k_IBL",
/// "r=0.25 Smith exact", ...
PlotTable g1_plot_table(int points = 200);

/// LearnOpenGL's F0 table (linear RGB).
struct FresnelMaterial {
  std::string name;
  glm::vec3 F0;
};
const std::vector<FresnelMaterial>& fresnel_materials();

/// Luminance of fresnelSchlick(v.h, F0) per material; v.h from 0 to 1.
/// Columns: "v.h", then the material names.
PlotTable fresnel_plot_table(int points = 201);

/// Directional albedo E(mu) = int f(wo, wi) cos(theta_i) dwi of a white metal
/// (baseColor 1, metallic 1, so F0 = 1) with the reference BRDF, integrated numerically by
/// sampling Brdf::sample with `samples` Owen-scrambled Sobol points per mu. Per roughness
/// three columns: "r=0.5 single" (multiscatter off), "r=0.5 multiscatter" (on), and
/// "r=0.5 table" (EnergyTable's tabulated E, which the single-scatter curve should match).
/// mu from 0.02 to 1.
PlotTable albedo_plot_table(int mu_points = 50, int samples = 4096);

}  // namespace pbrkit::cli
