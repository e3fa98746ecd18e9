// `pbrkit bake` outputs (see bake_output.h).
#include "pbrkit/ibl/bake_output.h"

#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "pbrkit/core/math.h"
#include "pbrkit/ibl/ktx2.h"
#include "pbrkit/ibl/prefilter.h"
#include "pbrkit/ibl/roughness_mapping.h"
#include "pbrkit/ibl/sheen_prefilter.h"
#include "pbrkit/image/image_io.h"
#include "pbrkit/util/atomic_file.h"
#include "pbrkit/util/error.h"

namespace pbrkit {

namespace fs = std::filesystem;

Image cube_cross(const std::array<Image, 6>& faces) {
  const int s = faces[0].width, ch = faces[0].channels;
  Image cross(4 * s, 3 * s, ch, 0.0f);
  // (column, row) of each face: +X, -X, +Y, -Y, +Z, -Z.
  const int cell[6][2] = {{2, 1}, {0, 1}, {1, 0}, {1, 2}, {1, 1}, {3, 1}};
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < s; ++y)
      for (int x = 0; x < s; ++x) {
        const float* src = faces[f].pixel(x, y);
        float* dst = cross.pixel(cell[f][0] * s + x, cell[f][1] * s + y);
        for (int c = 0; c < ch; ++c) dst[c] = src[c];
      }
  return cross;
}

void check_output_directory(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    fail("{}: cannot create the output directory ({})", dir.string(),
         ec ? ec.message() : "a file of that name exists");
  const fs::path probe = dir / ".pbrkit-write-test";
  {
    std::ofstream f(probe);
    if (!f || !(f << "x") || !f.flush()) {
      fs::remove(probe, ec);
      fail("{}: the output directory is not writable", dir.string());
    }
  }
  fs::remove(probe, ec);
}

namespace {

nlohmann::json vec(glm::vec3 v) {
  return nlohmann::json::array({v.x, v.y, v.z});
}

// Stages files in a temporary folder of the output directory, then moves them in.
class Staging {
 public:
  explicit Staging(const fs::path& dir) : dir_(dir) {
    std::random_device rd;
    tmp_ = dir / fmt::format(".pbrkit-bake-{:08x}", rd());
    fs::create_directories(tmp_);
  }
  ~Staging() {
    std::error_code ec;
    fs::remove_all(tmp_, ec);
  }
  fs::path path(const std::string& name) {
    names_.push_back(name);
    return tmp_ / name;
  }
  std::vector<std::string> commit() {
    for (const auto& name : names_) {
      std::error_code ec;
      fs::rename(tmp_ / name, dir_ / name, ec);
      if (ec) fail("{}: cannot move into place: {}", (dir_ / name).string(), ec.message());
    }
    return names_;
  }

 private:
  fs::path dir_, tmp_;
  std::vector<std::string> names_;
};

const char* method_name(const Cubemap& source, const BakeOptions& o, int level, int levels) {
  if (level == 0) return "copy of the source (mirror)";
  const float r = mip_roughness(level, levels, o.mapping);
  if (use_quadrature(source, o, r, source.size(level)))
    return "direct quadrature over a source level";
  return o.filtered_importance_sampling ? "GGX importance sampling + filtered importance sampling"
                                        : "GGX importance sampling";
}

}  // namespace

std::vector<std::string> write_bake_outputs(const fs::path& dir, const BakeResult& result,
                                            const BakeRecord& record,
                                            const BakeOutputOptions& options) {
  check_output_directory(dir);
  Staging stage(dir);
  const Ktx2Format cube_format =
      options.float32 ? Ktx2Format::kRgba32Float : Ktx2Format::kRgba16Float;
  const std::string writer = "pbrkit " PBRKIT_VERSION;
  auto ktx = [&](Ktx2Texture t, const std::string& name) {
    t.metadata.emplace_back("KTXwriter", writer);
    write_ktx2(stage.path(name), t);
  };
  ktx(ktx2_from_cubemap(result.specular, cube_format), "specular.ktx2");
  ktx(ktx2_from_cubemap(result.irradiance, cube_format), "irradiance.ktx2");
  for (const auto& [name, lut] :
       {std::pair<std::string, const Image*>{"reference", &record.lut_reference},
        {"classic", &record.lut_classic}}) {
    ktx(ktx2_from_image(*lut, Ktx2Format::kRgba16Float), "brdf_lut_" + name + ".ktx2");
    ktx(ktx2_from_image(*lut, Ktx2Format::kRgba32Float), "brdf_lut_" + name + "_f32.ktx2");
    write_exr(stage.path("brdf_lut_" + name + ".exr"), *lut, ExrPixelType::kFloat);
    if (options.previews)
      write_png(stage.path("preview_brdf_lut_" + name + ".png"), rgb_channels(*lut));
  }
  const int levels = result.specular.levels();
  for (int level = 0; level < levels; ++level) {
    const Image cross = rgb_channels(cube_cross(result.specular.mips[level]));
    if (options.exr)
      write_exr(stage.path(fmt::format("specular_mip{}.exr", level)), cross, ExrPixelType::kHalf);
    if (options.previews)
      write_png(stage.path(fmt::format("preview_specular_mip{}.png", level)),
                display_image(cross, options.preview));
  }
  // The sheen chain and LUT (ibl/sheen_prefilter.h, ibl/sheen_lut.h), written like the
  // specular chain and the BRDF LUTs.
  ktx(ktx2_from_cubemap(result.sheen, cube_format), "sheen.ktx2");
  ktx(ktx2_from_image(result.sheen_lut, Ktx2Format::kRgba16Float), "sheen_lut.ktx2");
  ktx(ktx2_from_image(result.sheen_lut, Ktx2Format::kRgba32Float), "sheen_lut_f32.ktx2");
  write_exr(stage.path("sheen_lut.exr"), result.sheen_lut, ExrPixelType::kFloat);
  if (options.previews)
    write_png(stage.path("preview_sheen_lut.png"), rgb_channels(result.sheen_lut));
  const int sheen_levels = result.sheen.levels();
  for (int level = 0; level < sheen_levels; ++level) {
    const Image cross = rgb_channels(cube_cross(result.sheen.mips[level]));
    if (options.exr)
      write_exr(stage.path(fmt::format("sheen_mip{}.exr", level)), cross, ExrPixelType::kHalf);
    if (options.previews)
      write_png(stage.path(fmt::format("preview_sheen_mip{}.png", level)),
                display_image(cross, options.preview));
  }
  {
    const Image cross = rgb_channels(cube_cross(result.irradiance.mips[0]));
    if (options.exr) write_exr(stage.path("irradiance.exr"), cross, ExrPixelType::kHalf);
    // Irradiance / pi is the radiance a white Lambertian surface reflects: comparable in
    // brightness with the specular previews.
    Image radiance = cross;
    for (float& v : radiance.data) v *= kInvPi;
    if (options.previews)
      write_png(stage.path("preview_irradiance.png"), display_image(radiance, options.preview));
  }

  // manifest.json
  nlohmann::json m;
  const Environment& env = *record.environment;
  const BakeOptions& o = record.options;
  m["generator"] = writer;
  m["source"] = {{"file", env.source},
                 {"width", env.map.width},
                 {"height", env.map.height},
                 {"rotation_deg", env.rotation_deg},
                 {"intensity", env.intensity}};
  m["orientation"] = {
      {"environment",
       "equirectangular, +Y up, row 0 = zenith; the image centre (u = 0.5) faces -Z, u = 0.75 "
       "faces +X; u = 0.5 + atan2(d.x, -d.z) / (2 pi), v = acos(d.y) / pi; rotation_deg turns "
       "the environment about +Y counter-clockwise seen from above (90: -Z moves to -X)"},
      {"cubemap",
       "OpenGL / Vulkan / KTX2 convention: faces +X, -X, +Y, -Y, +Z, -Z; (s, t) per OpenGL 4.5 "
       "table 8.19; row y holds t = (y + 0.5) / size, column x holds s = (x + 0.5) / size; "
       "KTXorientation rd"},
      {"exr_cross",
       "4x3 faces: row 0 [_, +Y, _, _], row 1 [-X, +Z, +X, -Z], row 2 [_, -Y, _, _]; faces "
       "as stored (the cube unfolded, seen from outside)"}};
  nlohmann::json spec_levels = nlohmann::json::array();
  for (int level = 0; level < levels; ++level)
    spec_levels.push_back({{"level", level},
                           {"size", result.specular.size(level)},
                           {"roughness", mip_roughness(level, levels, o.mapping)},
                           {"method", method_name(result.environment, o, level, levels)}});
  m["specular"] = {
      {"file", "specular.ktx2"},
      {"format", options.float32 ? "R32G32B32A32_SFLOAT" : "R16G16B16A16_SFLOAT"},
      {"face_size", o.face_size},
      {"levels", levels},
      {"roughness_mapping", roughness_mapping_name(o.mapping)},
      {"roughness_formula", "roughness = level / (levels - 1); alpha = max(roughness, 0.02)^2"},
      {"samples", o.samples},
      {"sampling", "Hammersley GGX NDF samples, n = v = R, weights n.l (Karis 2013)"},
      {"filtered_importance_sampling", o.filtered_importance_sampling},
      {"fis_lod", fmt::format("0.5 log2(Omega_s / Omega_p) + {}", kPrefilterLodBias)},
      {"model", std::string(brdf_model_name(o.model))},
      {"level_details", spec_levels},
      {"exr", "specular_mip<level>.exr (cross, half)"}};
  m["irradiance"] = {{"file", "irradiance.ktx2"},
                     {"face_size", o.irradiance_size},
                     {"convention",
                      "E(n) = integral L(w) max(0, n.w) dw (NOT divided by pi); "
                      "Lambertian radiance = baseColor / pi * E"},
                     {"exr", "irradiance.exr (cross, half)"}};
  nlohmann::json sh = nlohmann::json::array();
  for (const glm::vec3& c : result.sh) sh.push_back(vec(c));
  m["sh9"] = {{"coefficients", sh},
              {"order", "(l,m) = (0,0), (1,-1), (1,0), (1,1), (2,-2), (2,-1), (2,0), (2,1), (2,2)"},
              {"basis",
               "real SH, Y00 = 0.282095, Y1-1 = 0.488603 y, Y10 = 0.488603 z, Y11 = 0.488603 x, "
               "Y2-2 = 1.092548 xy, Y2-1 = 1.092548 yz, Y20 = 0.315392 (3z^2 - 1), "
               "Y21 = 1.092548 xz, Y22 = 0.546274 (x^2 - y^2)"},
              {"convention",
               "irradiance E(n) = sum c_i Y_i(n): the cosine-lobe convolution A_l (pi, 2pi/3, "
               "pi/4) is folded in (Ramamoorthi & Hanrahan 2001, eq. 8), 1/pi is NOT"}};
  m["brdf_lut"] = {
      {"size", o.lut_size},
      {"samples", 1024},
      {"axes", "x: n.v = (x + 0.5) / size; y: roughness = (y + 0.5) / size (row 0 smoothest)"},
      {"channels",
       "R = A (scale of F0), G = B (bias), B = E = A + B (single-scattering albedo for F0 = 1), "
       "A = E_avg(roughness) = 2 int E mu dmu (Fdez-Aguera 2019 / Kulla-Conty 2017)"},
      {"integration", "Hammersley visible-normal samples (Heitz 2018), weight F G / G1(v)"},
      {"reference",
       {{"G", "height-correlated Smith (Heitz 2014)"},
        {"files",
         {"brdf_lut_reference.ktx2", "brdf_lut_reference_f32.ktx2", "brdf_lut_reference.exr"}}}},
      {"classic",
       {{"G", "Schlick-GGX Smith product, k = alpha / 2"},
        {"files", {"brdf_lut_classic.ktx2", "brdf_lut_classic_f32.ktx2", "brdf_lut_classic.exr"}}}},
      {"formats", "*.ktx2 R16G16B16A16_SFLOAT, *_f32.ktx2 R32G32B32A32_SFLOAT, *.exr float32"}};
  nlohmann::json sheen_details = nlohmann::json::array();
  for (int level = 0; level < sheen_levels; ++level)
    sheen_details.push_back({{"level", level},
                             {"size", result.sheen.size(level)},
                             {"grid_size", sheen_grid_size(o, level)},
                             {"sheen_roughness", mip_roughness(level, sheen_levels, o.mapping)}});
  m["sheen"] = {
      {"file", "sheen.ktx2"},
      {"format", options.float32 ? "R32G32B32A32_SFLOAT" : "R16G16B16A16_SFLOAT"},
      {"face_size", result.sheen.size(0)},
      {"levels", sheen_levels},
      {"roughness_mapping", roughness_mapping_name(o.mapping)},
      {"roughness_formula",
       "sheenRoughness = level / (levels - 1), the specular chain's levels and sizes; "
       "r = max(sheenRoughness, 0.07)"},
      {"integral",
       "int L(l) D_Charlie(h) n.l dl / int D_Charlie(h) n.l dl, n = v = R (KHR_materials_sheen, "
       "Estevez & Kulla 2017); a constant environment gives the constant"},
      {"method",
       fmt::format("direct quadrature over a source level of at most {} px ({} for roughness >= "
                   "0.4; texel centres, exact solid angles) on a grid of at most {} px, "
                   "bilinearly upsampled to larger levels",
                   o.sheen_source_size, std::max(o.sheen_source_size / 2, 8), o.sheen_grid_size)},
      {"level_details", sheen_details},
      {"exr", "sheen_mip<level>.exr (cross, half)"}};
  m["sheen_lut"] = {
      {"size", result.sheen_lut.width},
      {"axes",
       "x: n.v = (x + 0.5) / size; y: sheenRoughness = (y + 0.5) / size (row 0 smoothest), "
       "clamped to >= 0.07"},
      {"channels",
       "R = DG = E_sheen(n.v, r) = int D_Charlie V_Charlie n.l dl (the split-sum scale of the "
       "sheen IBL AND the albedo scaling's E: one integral with the README's Charlie V), "
       "G = E_sheen_avg(r) = 2 int E_sheen mu dmu, B = 0, A = 1"},
      {"usage",
       "sheen_ibl = sheenColor * sheen(R, sheenRoughness) * lut.R; base *= 1 - max3(sheenColor) "
       "* lut.R"},
      {"files", {"sheen_lut.ktx2", "sheen_lut_f32.ktx2", "sheen_lut.exr"}},
      {"formats", "*.ktx2 R16G16B16A16_SFLOAT, *_f32.ktx2 R32G32B32A32_SFLOAT, *.exr float32"}};
  const BakeTimings& t = result.timings;
  m["timings_s"] = {
      {"cube", t.cube_s},
      {"specular", t.specular_s},
      {"irradiance", t.irradiance_s},
      {"sh", t.sh_s},
      {"lut_both_models", record.lut_both_s},
      {"sheen", t.sheen_s},
      {"total", t.cube_s + t.specular_s + t.irradiance_s + t.sh_s + record.lut_both_s + t.sheen_s}};
  if (!record.validation.empty()) {
    nlohmann::json v = nlohmann::json::array();
    for (const PrefilterError& e : record.validation)
      v.push_back({{"level", e.level},
                   {"roughness", e.roughness},
                   {"directions", e.directions},
                   {"mean_relative_error", e.mean_relative},
                   {"max_relative_error", e.max_relative}});
    m["validation"] = v;
  }
  write_bytes_atomically(stage.path("manifest.json"), m.dump(2) + "\n");
  return stage.commit();
}

}  // namespace pbrkit
