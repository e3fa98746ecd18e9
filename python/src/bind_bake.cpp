// bake(): the IBL pipeline of `pbrkit bake` (ibl/bake.h) from Python, returning its maps as
// arrays and optionally writing the usual files.
#include <pybind11/stl.h>

#include <cmath>
#include <optional>

#include "arrays.h"
#include "bindings.h"
#include "interrupt.h"
#include "pbrkit/ibl/bake.h"
#include "pbrkit/ibl/bake_output.h"
#include "pbrkit/ibl/brdf_lut.h"
#include "pbrkit/image/environment.h"

namespace py = pybind11;

namespace pbrkit::python {

namespace {

// One cube level as a (6, S, S, C) array, faces +X, -X, +Y, -Y, +Z, -Z (ibl/cubemap.h).
py::array_t<float> cube_level(const std::array<Image, 6>& faces) {
  const Image& f0 = faces[0];
  py::array_t<float> a(
      {py::ssize_t(6), py::ssize_t(f0.height), py::ssize_t(f0.width), py::ssize_t(f0.channels)});
  float* out = a.mutable_data();
  for (const Image& f : faces) out = std::copy(f.data.begin(), f.data.end(), out);
  return a;
}

py::list cube_levels(const Cubemap& cube) {
  py::list levels;
  for (const auto& level : cube.mips) levels.append(cube_level(level));
  return levels;
}

}  // namespace

void bind_bake(py::module_& m) {
  m.def(
      "_bake",
      [](const py::object& env, float rotation, float intensity, int face_size, int samples,
         int irradiance_size, int lut_size, const std::string& model, const py::object& out_dir,
         const py::object& progress) {
        if (!std::isfinite(rotation)) throw py::value_error("rotation must be finite");
        if (!(intensity >= 0.0f) || !std::isfinite(intensity))
          throw py::value_error("intensity must be a finite number >= 0");
        Environment e;
        if (py::isinstance<py::str>(env)) {
          const std::string s = env.cast<std::string>();
          e = load_environment_or_default(s == "builtin" ? "" : s, rotation, intensity);
        } else {
          e.map = image_from_array(env, "env", {3, 3, true, true});
          if (e.map.width != 2 * e.map.height)
            throw py::value_error("env: an environment must be equirectangular (shape (H, 2H, 3))");
          e.rotation_deg = rotation;
          e.intensity = intensity;
          e.source = "array";
        }
        BakeOptions o;
        o.face_size = face_size;
        o.samples = samples;
        o.irradiance_size = irradiance_size;
        o.lut_size = lut_size;
        if (model != "reference" && model != "classic")
          throw py::value_error("model must be 'reference' or 'classic'");
        o.model = parse_brdf_model(model);
        if (const auto problem = find_bake_options_problem(o))
          throw py::value_error(std::string(problem->name) + " " + problem->message);
        std::optional<std::string> dir;
        if (!out_dir.is_none()) dir = py::str(out_dir).cast<std::string>();
        if (dir) check_output_directory(*dir);

        BakeResult result;
        run_interruptible(
            [&](WorkControl& control) {
              result = bake_environment(e, o, control.callback());
              // Stopped early: what the bake has goes back to Python, but no partial set
              // of files is written.
              if (dir && !result.interrupted) {
                BakeRecord record;
                record.environment = &e;
                record.options = o;
                const BrdfModel other =
                    o.model == BrdfModel::kReference ? BrdfModel::kClassic : BrdfModel::kReference;
                const Image other_lut = compute_brdf_lut(other, o.lut_size);
                record.lut_reference = o.model == BrdfModel::kReference ? result.lut : other_lut;
                record.lut_classic = o.model == BrdfModel::kClassic ? result.lut : other_lut;
                write_bake_outputs(*dir, result, record, {});
              }
            },
            progress);

        py::dict d;
        // A bake stopped early (progress returned False) has the stages it finished:
        // the chains' finished levels, and the other entries only once computed.
        d["interrupted"] = result.interrupted;
        d["specular"] = cube_levels(result.specular);
        d["environment"] = cube_levels(result.environment);
        d["sheen"] = cube_levels(result.sheen);
        if (!result.irradiance.mips.empty()) {
          d["irradiance"] = cube_level(result.irradiance.mips.at(0));
          py::array_t<float> sh({9, 3});
          for (int i = 0; i < 9; ++i)
            for (int c = 0; c < 3; ++c) sh.mutable_at(i, c) = result.sh[std::size_t(i)][c];
          d["sh"] = sh;
        }
        if (!result.lut.data.empty()) d["lut"] = array_from_image(std::move(result.lut));
        if (!result.sheen_lut.data.empty())
          d["sheen_lut"] = array_from_image(std::move(result.sheen_lut));
        return d;
      },
      py::arg("env"), py::arg("rotation"), py::arg("intensity"), py::arg("face_size"),
      py::arg("samples"), py::arg("irradiance_size"), py::arg("lut_size"), py::arg("model"),
      py::arg("out_dir"), py::arg("progress"));
}

}  // namespace pbrkit::python
