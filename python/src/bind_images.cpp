// Images from Python: read and write (EXR, PNG, HDR), compare, tone map, denoise. The same
// library functions as `pbrkit compare`, the PNG outputs and `pbrkit denoise`.
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "arrays.h"
#include "bindings.h"
#include "interrupt.h"
#include "pbrkit/core/color.h"
#include "pbrkit/denoise/denoiser_choice.h"
#include "pbrkit/image/compare.h"
#include "pbrkit/image/display.h"
#include "pbrkit/image/image_io.h"
#include "pbrkit/image/output_paths.h"
#include "pbrkit/util/error.h"

namespace py = pybind11;

namespace pbrkit::python {

namespace {

std::string extension_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// A display image (sRGB-encoded colour in [0, 1], alpha last for 2 and 4 channels) in
// linear light: what read_image() returns for its PNG, before the quantisation.
Image linear_from_display(const Image& display) {
  Image linear = display;
  const bool alpha = display.channels == 2 || display.channels == 4;
  const int colour = display.channels - (alpha ? 1 : 0);
  for (std::size_t i = 0; i < linear.data.size(); ++i) {
    const float v = std::clamp(linear.data[i], 0.0f, 1.0f);
    linear.data[i] = int(i % std::size_t(linear.channels)) < colour ? srgb_decode(v) : v;
  }
  return linear;
}

void check_readable(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw py::value_error(path + ": no such file");  // replaced by FileNotFoundError in Python
}

}  // namespace

DenoiserChoice denoiser_choice(const std::optional<std::string>& name) {
  DenoiserChoice choice;
  if (!name) return choice;
  if (*name != "learned" && *name != "classic")
    throw py::value_error("denoiser must be 'learned' or 'classic', got '" + *name + "'");
  choice.kind = *name == "learned" ? DenoiserKind::kLearned : DenoiserKind::kClassic;
  return choice;
}

void bind_images(py::module_& m) {
  m.def(
      "read_image",
      [](const std::string& path) {
        check_readable(path);
        Image image;
        {
          py::gil_scoped_release release;
          image = read_image(path);
        }
        return array_from_image(std::move(image));
      },
      py::arg("path"),
      "Reads an EXR, HDR, PNG or JPEG as a float32 array (H, W[, C]): linear values (8/16-bit "
      "PNG and JPEG colour decoded from sRGB), the main layer of an EXR.");
  m.def(
      "read_exr_layers",
      [](const std::string& path) {
        check_readable(path);
        std::vector<std::pair<std::string, Image>> layers;
        {
          py::gil_scoped_release release;
          layers = read_exr_layers(path);
        }
        py::dict d;
        for (auto& [name, image] : layers) d[py::str(name)] = array_from_image(std::move(image));
        return d;
      },
      py::arg("path"),
      "Every layer of an EXR (e.g. a render's AOVs) as {name: array}; the main layer is ''.");
  m.def(
      "write_image",
      [](const std::string& path, const py::handle& array, bool half, int bits, float exposure,
         const std::string& tonemapper) {
        if (extension_of(path) == ".hdr") {
          Image image = image_from_array(array, "image", {3, 3, true, false});
          py::gil_scoped_release release;
          write_hdr(path, image);
          return;
        }
        // The one rule of every image output (image/output_paths.h), checked before any work.
        ImageOutputPaths outputs;
        try {
          outputs = image_output_paths(path, "path");
        } catch (const Error& e) {
          throw py::value_error(std::string(e.what()) + "; or .hdr, written alone");
        }
        if (bits != 8 && bits != 16) throw py::value_error("bits must be 8 or 16");
        if (!std::isfinite(exposure)) throw py::value_error("exposure must be finite");
        const ExrPixelType exr_type = half ? ExrPixelType::kHalf : ExrPixelType::kFloat;
        if (extension_of(path) == ".exr") {
          const DisplaySettings settings{exposure, parse_tone_mapper(tonemapper)};
          Image linear = image_from_array(array, "image", {1, 4, false, false});
          py::gil_scoped_release release;
          create_output_directory(outputs);
          write_exr(outputs.exr, linear, exr_type);
          write_png(outputs.png, display_image(linear, settings), bits);
        } else {
          Image display = image_from_array(array, "image", {1, 4, true, false});
          py::gil_scoped_release release;
          create_output_directory(outputs);
          write_png(outputs.png, display, bits);
          write_exr(outputs.exr, linear_from_display(display), exr_type);
        }
      },
      py::arg("path"), py::arg("image"), py::arg("half") = false, py::arg("bits") = 8,
      py::arg("exposure") = 0.0f, py::arg("tonemapper") = "pbr-neutral",
      "Writes an image atomically, named as `pbrkit render -o` names its outputs: a .exr or "
      ".png path writes that file and the other beside it, with the same stem (any other name "
      "is a ValueError, but .hdr). .exr: `image` holds linear values, written as 32-bit floats "
      "(halves with half=True), and the PNG beside it is their display transform (exposure "
      "and tonemapper as tonemap() takes them). .png: `image` holds display-referred values "
      "in [0, 1] (clamped; tonemap() makes them from linear ones), 8 or 16 bits, and the EXR "
      "beside it the same image in linear light (the sRGB curve undone, as read_image() reads "
      "the PNG, without the quantisation). .hdr: linear RGB, that file alone.");
  m.def(
      "compare",
      [](const py::handle& a, const py::handle& b, const py::object& mask) {
        const Image ia = image_from_array(a, "a"), ib = image_from_array(b, "b");
        std::optional<Image> im;
        if (!mask.is_none()) im = image_from_array(mask, "mask");
        CompareMetrics c;
        {
          py::gil_scoped_release release;
          c = compare_images(ia, ib, im ? &*im : nullptr, "a", "b", "mask");
        }
        py::dict d;
        d["rmse"] = c.rmse;
        d["mse"] = c.mse;
        d["relative_mse"] = c.relative_mse;
        d["psnr"] = c.psnr;
        d["mean_relative_error"] = c.mean_relative_error;
        d["pixels"] = c.pixels;
        return d;
      },
      py::arg("a"), py::arg("b"), py::arg("mask") = py::none(),
      "Compares `a` (test) with `b` (reference) as `pbrkit compare` does: rmse, mse, "
      "relative_mse (mean (a-b)^2/(b^2+0.01)), psnr (peak 1), mean_relative_error, pixels.");
  m.def(
      "tonemap",
      [](const py::handle& linear, float exposure, const std::string& tonemapper) {
        if (!std::isfinite(exposure)) throw py::value_error("exposure must be finite");
        const DisplaySettings settings{exposure, parse_tone_mapper(tonemapper)};
        Image image = image_from_array(linear, "image", {1, 4, true, false});
        Image display;
        {
          py::gil_scoped_release release;
          display = display_image(image, settings);
        }
        return array_from_image(std::move(display));
      },
      py::arg("image"), py::arg("exposure") = 0.0f, py::arg("tonemapper") = "pbr-neutral",
      "The display transform of pbrkit's PNGs: 2^exposure, the tone mapper (none, "
      "pbr-neutral, aces, agx), then sRGB encoding; returns (H, W, 3) values in [0, 1].");
  m.def("tonemappers", &tone_mapper_names, "The tone mappers tonemap() knows.");
  m.def(
      "_denoise",
      [](const std::vector<py::object>& halves, const std::optional<std::string>& denoiser,
         const py::object& progress) {
        DenoiseInput in;
        const char* names[4] = {"color", "albedo", "normal", "depth"};
        Image* slots[4] = {in.color, in.albedo, in.normal, in.depth};
        for (int k = 0; k < 4; ++k)
          for (int h = 0; h < 2; ++h)
            slots[k][h] = image_from_array(
                halves[std::size_t(2 * k + h)], std::string(names[k]) + (h ? "[1]" : "[0]"),
                k == 3 ? ArrayRequirements{1, 1} : ArrayRequirements{3, 3});
        validate_denoise_input(in);
        const DenoiserChoice choice = denoiser_choice(denoiser);
        Image out;
        run_interruptible(
            [&](WorkControl& control) {
              out = denoise_render(in, choice, control.callback()).image;
            },
            progress);
        return array_from_image(std::move(out));
      },
      py::arg("halves"), py::arg("denoiser"), py::arg("progress"));
}

}  // namespace pbrkit::python
