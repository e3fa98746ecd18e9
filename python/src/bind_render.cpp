// render(): the path tracer or the OpenGL renderer from Python, with the CLI's defaults
// (apps/pbrkit/cmd_render_path.cpp, cmd_render_gl.cpp), so that an array returned here
// equals the EXR `pbrkit render` writes for the same scene, options and seed.
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "arrays.h"
#include "bindings.h"
#include "interrupt.h"
#include "pbrkit/core/brdf.h"
#include "pbrkit/denoise/denoiser_choice.h"
#include "pbrkit/denoise/inputs.h"
#include "pbrkit/gl/context.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/ibl/bake.h"
#include "pbrkit/image/display.h"
#include "pbrkit/image/environment.h"
#include "pbrkit/pt/path_tracer.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/load.h"
#include "pbrkit/scene/pose.h"
#include "pbrkit/scene/variants.h"
#include "pbrkit/util/error.h"
#include "scene_handle.h"

namespace py = pybind11;

namespace pbrkit::python {

namespace {

// The environment argument: "builtin" (pbrkit's default map), a file path, an (H, 2H, 3|4)
// float32 array of linear radiance (equirectangular, row 0 the zenith), or None.
std::optional<Environment> environment_from(const py::object& env, float rotation,
                                            float intensity) {
  if (!std::isfinite(rotation)) throw py::value_error("env_rotation must be finite");
  if (!(intensity >= 0.0f) || !std::isfinite(intensity))
    throw py::value_error("env_intensity must be a finite number >= 0");
  if (env.is_none()) return std::nullopt;
  if (py::isinstance<py::str>(env)) {
    const std::string s = env.cast<std::string>();
    return load_environment_or_default(s == "builtin" ? "" : s, rotation, intensity);
  }
  Environment e;
  e.map = image_from_array(env, "env", {3, 4, true, true});
  if (e.map.width != 2 * e.map.height)
    throw py::value_error(
        "env: an environment must be equirectangular with a 2:1 aspect ratio "
        "(shape (H, 2H, 3)), got " +
        std::to_string(e.map.height) + "x" + std::to_string(e.map.width));
  if (e.map.channels == 4) e.map = rgb_channels(e.map);
  e.rotation_deg = rotation;
  e.intensity = intensity;
  e.source = "array";
  return e;
}

RenderView view_from(const Scene& scene, const py::object& camera, std::optional<int> width,
                     std::optional<int> height) {
  for (const auto& [v, name] : {std::pair{width, "width"}, std::pair{height, "height"}})
    if (v && (*v < 1 || *v > 16384))
      throw py::value_error(std::string(name) + " must be in 1..16384");
  if (py::isinstance<Camera>(camera)) {
    const Camera c = camera.cast<Camera>();
    return {c, image_size(c, width, height)};
  }
  std::optional<int> index;
  if (!camera.is_none()) {
    if (!py::isinstance<py::int_>(camera))
      throw py::type_error("camera: expected None, a camera index or a pbrkit.Camera");
    index = camera.cast<int>();
    if (*index < 0 || std::size_t(*index) >= scene.cameras.size())
      throw py::index_error("camera " + std::to_string(*index) + ": the scene has " +
                            std::to_string(scene.cameras.size()) + " camera(s)");
  }
  return select_view(scene, index, width, height);
}

BrdfOptions brdf_options(const std::string& model, std::optional<bool> multiscatter) {
  BrdfOptions o;
  o.model = parse_brdf_model(model);
  o.multiscatter = multiscatter.value_or(default_multiscatter(o.model));
  return o;
}

struct PathArgs {
  std::optional<std::uint32_t> spp;
  std::optional<std::uint32_t> seed;
  std::optional<int> max_bounces;
  std::optional<double> time;
  std::optional<float> noise_threshold;
  std::optional<int> threads;
  std::optional<bool> denoise;
  std::optional<std::string> denoiser;
  std::optional<std::vector<std::string>> aovs;
  std::optional<std::string> light_sampler;
  std::optional<std::string> guiding;
  std::vector<std::string> given() const {
    std::vector<std::string> names;
    if (spp) names.push_back("spp");
    if (seed) names.push_back("seed");
    if (max_bounces) names.push_back("max_bounces");
    if (time) names.push_back("time");
    if (noise_threshold) names.push_back("noise_threshold");
    if (threads) names.push_back("threads");
    if (denoise) names.push_back("denoise");
    if (denoiser) names.push_back("denoiser");
    if (aovs) names.push_back("aovs");
    if (light_sampler) names.push_back("light_sampler");
    if (guiding) names.push_back("guiding");
    return names;
  }
};

const std::vector<std::string>& aov_names() {
  static const std::vector<std::string> names{"albedo", "normal", "depth", "samples", "noise"};
  return names;
}

py::object render_path_tracer(const Scene& scene, const std::optional<Environment>& env,
                              const RenderView& view, const BrdfOptions& brdf, const PathArgs& a,
                              const py::object& progress,
                              const PathTracerSettings::Shutter& shutter) {
  PathTracerSettings s;
  s.shutter = shutter;
  s.width = view.size.width;
  s.height = view.size.height;
  if (a.spp) {
    if (*a.spp < 1 || *a.spp > (1u << 24)) throw py::value_error("spp must be in 1..16777216");
    s.spp = *a.spp;
  }
  if (a.time) {
    if (!(*a.time >= 0.0) || !std::isfinite(*a.time))
      throw py::value_error("time must be a finite number of seconds >= 0");
    s.time_limit = *a.time;
  }
  if (a.noise_threshold) {
    if (!(*a.noise_threshold >= 0.0f) || !std::isfinite(*a.noise_threshold))
      throw py::value_error("noise_threshold must be a finite number >= 0");
    s.noise_threshold = *a.noise_threshold;
  }
  s.min_spp = std::min(s.min_spp, s.spp);
  if (a.max_bounces) {
    if (*a.max_bounces < 0 || *a.max_bounces > 1024)
      throw py::value_error("max_bounces must be in 0..1024");
    s.max_bounces = *a.max_bounces;
  }
  if (a.seed) s.seed = *a.seed;
  if (a.threads) {
    if (*a.threads < 0 || *a.threads > 1024) throw py::value_error("threads must be in 0..1024");
    s.threads = *a.threads;
  }
  s.brdf = brdf;
  s.checkpoint_interval = 0.0;
  if (a.light_sampler) {
    if (*a.light_sampler != "bvh" && *a.light_sampler != "power")
      throw py::value_error("light_sampler must be 'bvh' or 'power', got '" + *a.light_sampler +
                            "'");
    s.light_sampler = parse_light_sampler(*a.light_sampler);
  }
  if (a.guiding) {
    if (*a.guiding != "off" && *a.guiding != "on")
      throw py::value_error("guiding must be 'off' or 'on', got '" + *a.guiding + "'");
    s.guiding = parse_guiding(*a.guiding);
  }
  const std::vector<std::string> aovs = a.aovs.value_or(std::vector<std::string>{});
  for (const std::string& name : aovs)
    if (std::find(aov_names().begin(), aov_names().end(), name) == aov_names().end())
      throw py::value_error("aovs: unknown '" + name +
                            "' (known: albedo, normal, depth, samples, noise)");
  const bool denoising = a.denoise.value_or(false);
  // The weights are loaded before the render (a bad file fails first), once.
  const DenoiserChoice choice = denoiser_choice(a.denoiser);
  const LoadedDenoiser denoiser = denoising ? load_denoiser(choice) : LoadedDenoiser{choice, {}};

  std::optional<PathTracerResult> result;
  std::optional<Image> denoised;
  run_interruptible(
      [&](WorkControl& control) {
        s.stop = &control.stop;
        result = render_path(scene, env ? &*env : nullptr, view.camera, s, control.callback());
        if (denoising && !control.stop.load()) {
          // Stopped while denoising: the raw image, as a stopped render returns its samples.
          DenoiseRun run =
              denoise_render(denoise_input(result->film), denoiser, control.callback());
          if (!run.interrupted) denoised = std::move(run.image);
        }
      },
      progress);

  const Film& film = result->film;
  py::dict layers;
  for (const std::string& name : aovs) {
    if (name == "albedo") layers[name.c_str()] = array_from_image(film.albedo_image());
    if (name == "normal") layers[name.c_str()] = array_from_image(film.normal_image());
    if (name == "depth") layers[name.c_str()] = array_from_image(film.depth_image());
    if (name == "samples") layers[name.c_str()] = array_from_image(film.count_image());
    if (name == "noise") layers[name.c_str()] = array_from_image(film.noise_image());
  }
  py::object image;
  if (denoised) {
    if (!aovs.empty()) layers["raw"] = array_from_image(std::move(result->color));
    image = array_from_image(std::move(*denoised));
  } else {
    image = array_from_image(std::move(result->color));
  }
  if (aovs.empty()) return image;
  return py::make_tuple(image, layers);
}

py::object render_gl(const Scene& scene, const std::optional<Environment>& env,
                     const RenderView& view, const BrdfOptions& brdf, float env_rotation,
                     float env_intensity, const py::object& progress) {
  gl::RenderSettings settings;
  settings.brdf = brdf;
  settings.env_rotation_deg = env_rotation;
  settings.env_intensity = env_intensity;
  Image frame;
  run_interruptible(
      [&](WorkControl&) {
        BakeOptions bake = gl::realtime_bake_options();
        bake.model = brdf.model;
        gl::HeadlessContext context;
        gl::Renderer renderer;
        renderer.set_scene(scene);
        renderer.set_environment_light(env ? &*env : nullptr, bake);
        renderer.render(view.camera, view.size.width, view.size.height, settings);
        frame = rgb_channels(renderer.read_back());
      },
      progress);
  return array_from_image(std::move(frame));
}

}  // namespace

void bind_render(py::module_& m) {
  m.def(
      "_render",
      [](const SceneHandle& handle, const std::string& renderer, std::optional<int> width,
         std::optional<int> height, const py::object& env, float env_rotation, float env_intensity,
         const py::object& camera, const std::string& model, std::optional<bool> multiscatter,
         const py::object& progress, PathArgs path, const py::object& variant,
         const py::object& animation, double animation_time, const py::object& shutter) {
        // A variant switches the materials of a copy, and an animation poses a copy: the
        // Scene object is shared, and keeps its own materials and pose.
        std::shared_ptr<const Scene> varied = handle.scene;
        PoseTime pose =
            pose_argument(*handle.scene, animation, animation_time, "animation", "animation_time");
        // shutter=(open, close): seconds around animation_time, as --shutter OPEN:CLOSE; the
        // scene is posed at its centre, the path tracer samples a time per path.
        PathTracerSettings::Shutter blur;
        if (!shutter.is_none()) {
          if (animation.is_none()) throw py::value_error("shutter: needs animation");
          double open = 0.0, close = 0.0;
          try {
            const auto pair = shutter.cast<std::pair<double, double>>();
            open = pair.first;
            close = pair.second;
          } catch (const py::cast_error&) {
            throw py::type_error("shutter: expected None or (open, close) in seconds");
          }
          if (!std::isfinite(open) || !std::isfinite(close) || !(open < close))
            throw py::value_error("shutter: (open, close) must be finite with open < close");
          blur = {pose.animation, float(animation_time + open), float(animation_time + close),
                  blur.steps};
          pose.time = float(animation_time + 0.5 * (open + close));
        }
        if (!variant.is_none() || !animation.is_none()) {
          auto copy = std::make_shared<Scene>(*handle.scene);
          if (!variant.is_none()) {
            if (!py::isinstance<py::str>(variant) && !py::isinstance<py::int_>(variant))
              throw py::type_error("variant: expected None, a variant's name or its index");
            try {
              apply_variant(*copy, find_variant(*copy, py::str(variant).cast<std::string>()));
            } catch (const Error& e) {
              throw py::value_error(std::string("variant: ") + e.what());
            }
          }
          if (!animation.is_none()) pose_scene(*copy, pose);
          varied = std::move(copy);
        }
        const Scene& scene = *varied;
        if (renderer != "path" && renderer != "gl")
          throw py::value_error("renderer must be 'path' or 'gl', got '" + renderer + "'");
        if (model != "reference" && model != "classic")
          throw py::value_error("model must be 'reference' or 'classic', got '" + model + "'");
        if (!progress.is_none() && !PyCallable_Check(progress.ptr()))
          throw py::type_error("progress: expected a callable (fraction, detail) or None");
        if (renderer == "gl" && !path.given().empty()) {
          std::string names;
          for (const std::string& n : path.given()) names += (names.empty() ? "" : ", ") + n;
          throw py::value_error("renderer='gl' does not take " + names +
                                ": path tracer option(s), which it would ignore");
        }
        const std::optional<Environment> environment =
            environment_from(env, env_rotation, env_intensity);
        const RenderView view = view_from(scene, camera, width, height);
        const BrdfOptions brdf = brdf_options(model, multiscatter);
        if (renderer == "gl")
          return render_gl(scene, environment, view, brdf, env_rotation, env_intensity, progress);
        return render_path_tracer(scene, environment, view, brdf, path, progress, blur);
      },
      py::arg("scene"), py::arg("renderer"), py::arg("width"), py::arg("height"), py::arg("env"),
      py::arg("env_rotation"), py::arg("env_intensity"), py::arg("camera"), py::arg("model"),
      py::arg("multiscatter"), py::arg("progress"), py::arg("path"), py::arg("variant"),
      py::arg("animation"), py::arg("animation_time"), py::arg("shutter"));

  py::class_<PathArgs>(m, "_PathArgs")
      .def(py::init<>())
      .def_readwrite("spp", &PathArgs::spp)
      .def_readwrite("seed", &PathArgs::seed)
      .def_readwrite("max_bounces", &PathArgs::max_bounces)
      .def_readwrite("time", &PathArgs::time)
      .def_readwrite("noise_threshold", &PathArgs::noise_threshold)
      .def_readwrite("threads", &PathArgs::threads)
      .def_readwrite("denoise", &PathArgs::denoise)
      .def_readwrite("denoiser", &PathArgs::denoiser)
      .def_readwrite("aovs", &PathArgs::aovs)
      .def_readwrite("light_sampler", &PathArgs::light_sampler)
      .def_readwrite("guiding", &PathArgs::guiding);
}

}  // namespace pbrkit::python
