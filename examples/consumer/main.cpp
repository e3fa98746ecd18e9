// Renders the built-in `spheres` scene with pbrkit's path tracer and with its OpenGL
// renderer (headless EGL) through the installed library, and writes both as EXR and PNG:
//   consumer OUTPUT_DIR
// The settings are those of `pbrkit render spheres --width 128 --height 128` with
// `--spp 16 --noise-threshold 0 --seed 7` (path) and `--msaa 1` (gl), so CI can compare
// the images with the installed CLI's, bit for bit.
#include <cstdio>
#include <exception>
#include <filesystem>

#include "pbrkit/gl/context.h"
#include "pbrkit/gl/renderer.h"
#include "pbrkit/ibl/bake.h"
#include "pbrkit/image/display.h"
#include "pbrkit/image/environment.h"
#include "pbrkit/image/image_io.h"
#include "pbrkit/pt/path_tracer.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/load.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: consumer OUTPUT_DIR\n");
    return 2;
  }
  try {
    const std::filesystem::path out = argv[1];
    std::filesystem::create_directories(out);
    const pbrkit::Scene scene = pbrkit::load_scene("spheres");
    // The default environment ships with pbrkit (found beside the installed library).
    const pbrkit::Environment env = pbrkit::load_environment_or_default("", 0.0f, 1.0f);
    const pbrkit::RenderView view = pbrkit::select_view(scene, std::nullopt, 128, 128);

    pbrkit::PathTracerSettings path;
    path.width = view.size.width;
    path.height = view.size.height;
    path.spp = 16;
    path.noise_threshold = 0.0f;
    path.seed = 7;
    const pbrkit::PathTracerResult traced = pbrkit::render_path(scene, &env, view.camera, path);
    pbrkit::write_exr(out / "path.exr", traced.color, pbrkit::ExrPixelType::kFloat);
    pbrkit::write_display_png(out / "path.png", traced.color, {});

    pbrkit::gl::HeadlessContext context;
    pbrkit::gl::Renderer renderer;
    pbrkit::gl::RenderSettings gl;
    gl.msaa = 1;
    renderer.set_scene(scene);
    renderer.set_environment_light(&env);  // the background and the IBL baked from it
    renderer.render(view.camera, view.size.width, view.size.height, gl);
    const pbrkit::Image frame = pbrkit::rgb_channels(renderer.read_back());
    pbrkit::write_exr(out / "gl.exr", frame, pbrkit::ExrPixelType::kFloat);
    pbrkit::write_display_png(out / "gl.png", frame, {});
    std::printf("wrote path.exr, path.png, gl.exr, gl.png in %s\n", out.string().c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 1;
  }
  return 0;
}
