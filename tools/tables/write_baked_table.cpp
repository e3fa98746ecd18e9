// Regenerates a table the library bakes into its sources (pbrt-v4 keeps such generators
// as small programs beside the code, as cmd/rgb2spec_opt.cpp):
//
//   write_baked_table anisotropic-albedo src/pbrkit/ibl/anisotropic_albedo_data.inc  (~1 s)
//   write_baked_table dielectric-energy  src/pbrkit/core/dielectric_energy_data.inc  (~20 s)
//   write_baked_table anisotropic-energy src/pbrkit/core/anisotropic_energy_data.inc (~15 s)
//
// on two cores. The tests check the baked values against the computation they come from
// (tests/ibl/anisotropic_albedo_test.cpp, tests/core/transmission_test.cpp); this program
// writes them, atomically, when that computation changes.
#include <cstdio>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "pbrkit/core/anisotropic_energy.h"
#include "pbrkit/core/energy.h"
#include "pbrkit/ibl/anisotropic_albedo.h"
#include "pbrkit/util/atomic_file.h"
#include "pbrkit/util/error.h"

namespace {

std::string array(const char* name, const std::vector<float>& v) {
  std::string out = fmt::format("constexpr float {}[] = {{\n", name);
  for (std::size_t k = 0; k < v.size(); ++k)
    out += fmt::format("{}{}", fmt::format("{:#.7g}f,", double(v[k])), k % 8 == 7 ? "\n" : " ");
  return out + "};\n";
}

std::string anisotropic_albedo() {
  return "// The anisotropic GGX lobe's albedo at the table's nodes, baked by "
         "AnisotropicAlbedoTable::compute\n// (a 32 x 64 lattice an entry), written by "
         "tools/tables/write_baked_table.cpp. Layout:\n// ibl/anisotropic_albedo.h. Do not "
         "edit.\n" +
         array("kBakedAlbedo", pbrkit::AnisotropicAlbedoTable::compute());
}

std::string dielectric_energy() {
  std::vector<float> E, R_avg;
  pbrkit::DielectricEnergyTable::compute(pbrkit::DielectricEnergyTable::kSamples, E, R_avg);
  return fmt::format(
             "// The directional albedo of the rough dielectric interface, baked by "
             "DielectricEnergyTable::compute\n// ({} VNDF points an entry), written by "
             "tools/tables/write_baked_table.cpp. Layout: core/energy.h.\n// Do not edit.\n",
             pbrkit::DielectricEnergyTable::kSamples) +
         array("kBakedE", E) + array("kBakedRavg", R_avg);
}

std::string anisotropic_energy() {
  return fmt::format(
             "// The anisotropic GGX lobe's multiple-scattering compensation (E_ss, h, E_tot a "
             "node, then\n// E_ss_avg, E_tot_avg a slice), baked by "
             "AnisotropicEnergyTable::compute ({} x {} VNDF points\n// an integral, {} "
             "Sinkhorn iterations), written by tools/tables/write_baked_table.cpp. Layout:\n// "
             "core/anisotropic_energy.h. Do not edit.\n",
             pbrkit::AnisotropicEnergyTable::kLattice, pbrkit::AnisotropicEnergyTable::kLattice,
             pbrkit::AnisotropicEnergyTable::kIterations) +
         array("kBakedAnisotropicEnergy", pbrkit::AnisotropicEnergyTable::compute());
}

}  // namespace

int main(int argc, char** argv) {
  const std::string which = argc == 3 ? argv[1] : "";
  if (which != "anisotropic-albedo" && which != "dielectric-energy" &&
      which != "anisotropic-energy") {
    std::fprintf(stderr,
                 "usage: write_baked_table "
                 "anisotropic-albedo|dielectric-energy|anisotropic-energy OUTPUT.inc\n");
    return 2;
  }
  try {
    const std::string text = which == "anisotropic-albedo"   ? anisotropic_albedo()
                             : which == "anisotropic-energy" ? anisotropic_energy()
                                                             : dielectric_energy();
    pbrkit::write_bytes_atomically(argv[2], text);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "write_baked_table: %s\n", e.what());
    return 1;
  }
  std::printf("wrote %s\n", argv[2]);
  return 0;
}
