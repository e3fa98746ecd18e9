// pbrkit merge: combines accumulation EXRs written by 'pbrkit render --sample-range A:B'
// (on one machine or many) into the final image. Because every sample has weight 1 (the
// pixel filter is importance-sampled), merging is a sum of sums and counts, so N disjoint
// ranges merged equal one render of their union (to float rounding).
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "accumulation.h"
#include "commands.h"
#include "denoising.h"
#include "pbrkit/core/color.h"
#include "pbrkit/denoise/inputs.h"
#include "pbrkit/image/display.h"
#include "pbrkit/image/image_io.h"
#include "pbrkit/image/output_paths.h"
#include "pbrkit/pt/film.h"
#include "pbrkit/pt/path_tracer.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/log.h"

namespace pbrkit::cli {

namespace {

struct MergeOptions {
  std::vector<std::string> parts;
  std::string output;
  std::vector<std::string> aovs;
  float exposure = 0.0f;
  std::string tonemap = "pbr-neutral";
  bool full_float = false;
  std::string accumulation;
  bool denoise = false;
  DenoiserFlags denoiser;
};

}  // namespace

void register_merge_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "merge",
      "Combine accumulation EXRs from 'pbrkit render --sample-range A:B' into one render "
      "(a PNG and a linear EXR beside it)");
  auto o = std::make_shared<MergeOptions>();
  cmd->add_option("parts", o->parts, "accumulation EXRs (disjoint sample ranges)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", o->output,
                  "output .png or .exr; both are written, the other beside it")
      ->required();
  cmd->add_option("--aov", o->aovs, "extra EXR layers: albedo, normal, depth, samples, noise")
      ->delimiter(',')
      ->check(CLI::IsMember(render_aov_names()));
  cmd->add_option("--exposure", o->exposure, "exposure in EV for the PNG")->capture_default_str();
  cmd->add_option("--tonemap", o->tonemap, "tone mapper for the PNG")
      ->check(CLI::IsMember(tone_mapper_names()))
      ->capture_default_str();
  cmd->add_flag("--denoise", o->denoise,
                "denoise the merged image (the EXR keeps the raw image and the albedo, normal "
                "and depth as layers)");
  add_denoiser_options(*cmd, &o->denoiser);
  cmd->add_flag("--float", o->full_float, "write the EXR as 32-bit floats (default half)");
  cmd->add_option("--accumulation", o->accumulation,
                  "also write the merged accumulation EXR here (to merge again later)");
  cmd->callback([o] {
    const ImageOutputPaths outputs = image_output_paths(o->output, "-o");
    const LoadedDenoiser denoiser = o->denoise ? o->denoiser.load() : LoadedDenoiser{};
    Film film = read_accumulation(o->parts.front());
    for (std::size_t i = 1; i < o->parts.size(); ++i) {
      const Film part = read_accumulation(o->parts[i]);
      if (part.width != film.width || part.height != film.height)
        fail("{}: is {}x{} but {} is {}x{}; parts of one render have the same size", o->parts[i],
             part.width, part.height, o->parts.front(), film.width, film.height);
      film.merge(part);
    }
    // The parts' counts of what their renders could not represent, summed (film.h).
    if (film.non_finite_samples > 0)
      warn("the parts hold {} samples whose radiance was not finite (NaN or infinite, set to 0)",
           film.non_finite_samples);
    if (film.medium_overflows > 0)
      warn("the parts hold {} paths inside more than {} nested volumes (the limit)",
           film.medium_overflows, kMaxNestedVolumes);
    create_output_directory(outputs);
    const std::string& exr = outputs.exr;
    if (!o->accumulation.empty()) write_film(o->accumulation, film);
    const auto type = o->full_float ? ExrPixelType::kFloat : ExrPixelType::kHalf;
    if (o->denoise) {
      const Image denoised = *run_denoiser(denoise_input(film), denoiser);
      write_render_exr(exr, film, with_denoise_aovs(o->aovs), type, &denoised);
      write_display_png(outputs.png, denoised, {o->exposure, parse_tone_mapper(o->tonemap)});
    } else {
      write_render_exr(exr, film, o->aovs, type);
      write_display_png(outputs.png, film.color(), {o->exposure, parse_tone_mapper(o->tonemap)});
    }
    note("merged {} parts into {} and {}", o->parts.size(), outputs.png, exr);
  });
}

}  // namespace pbrkit::cli
