// pbrkit denoise: denoises a render's EXR that holds the half-buffer layers the denoiser
// reads ('pbrkit render --aov denoise' or 'pbrkit merge --aov denoise' writes them) and
// writes the denoised PNG and EXR (the EXR keeps the raw image and the AOVs as layers).
#include <memory>
#include <string>

#include "commands.h"
#include "denoising.h"
#include "pbrkit/core/color.h"
#include "pbrkit/denoise/inputs.h"
#include "pbrkit/image/display.h"
#include "pbrkit/image/image_io.h"
#include "pbrkit/image/output_paths.h"
#include "pbrkit/util/log.h"

namespace pbrkit::cli {

namespace {

struct DenoiseCommandOptions {
  std::string input;
  std::string output;
  float exposure = 0.0f;
  std::string tonemap = "pbr-neutral";
  bool full_float = false;
  DenoiserFlags denoiser;
};

// The library names the missing layers; the command adds the flag that writes them.
DenoiseInput read_input(const std::string& path) {
  try {
    return read_denoise_input(path);
  } catch (const MissingDenoiseLayers& e) {
    throw Error(fmt::format("{} (render with '--aov denoise' to write them)", e.what()));
  }
}

}  // namespace

void register_denoise_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "denoise",
      "Denoise a path-traced EXR written with '--aov denoise' (its half-buffer layers); "
      "writes the denoised image as a PNG and a linear EXR beside it");
  auto o = std::make_shared<DenoiseCommandOptions>();
  cmd->add_option("input", o->input, "EXR with the layers color_a, color_b, albedo_a, ...")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", o->output,
                  "output .png or .exr; both are written, the other beside it")
      ->required();
  cmd->add_option("--exposure", o->exposure, "exposure in EV for the PNG")->capture_default_str();
  cmd->add_option("--tonemap", o->tonemap, "tone mapper for the PNG")
      ->check(CLI::IsMember(tone_mapper_names()))
      ->capture_default_str();
  cmd->add_flag("--float", o->full_float, "write the EXR as 32-bit floats (default half)");
  add_denoiser_options(*cmd, &o->denoiser);
  cmd->callback([o] {
    const ImageOutputPaths outputs = image_output_paths(o->output, "-o");
    const LoadedDenoiser denoiser = o->denoiser.load();
    const DenoiseInput input = read_input(o->input);
    const std::optional<Image> denoised = run_denoiser(input, denoiser);
    create_output_directory(outputs);
    const auto type = o->full_float ? ExrPixelType::kFloat : ExrPixelType::kHalf;
    const Image raw = mean_of_halves(input.color);
    const Image albedo = mean_of_halves(input.albedo);
    const Image normal = mean_of_halves(input.normal);
    const Image depth = mean_of_halves(input.depth);
    write_exr_layers(outputs.exr, {{"", {"R", "G", "B"}, &*denoised, type},
                                   {"raw", {"R", "G", "B"}, &raw, type},
                                   {"albedo", {"R", "G", "B"}, &albedo, type},
                                   {"normal", {"X", "Y", "Z"}, &normal, type},
                                   {"depth", {"Z"}, &depth, ExrPixelType::kFloat}});
    write_display_png(outputs.png, *denoised, {o->exposure, parse_tone_mapper(o->tonemap)});
    note("denoised {} ({} denoiser) into {} and {}", o->input, denoiser_name(denoiser.choice.kind),
         outputs.png, outputs.exr);
  });
}

}  // namespace pbrkit::cli
