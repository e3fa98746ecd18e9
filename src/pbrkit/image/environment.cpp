#include "pbrkit/image/environment.h"

#include <cmath>

#include "pbrkit/core/equirect.h"
#include "pbrkit/image/image_io.h"
#include "pbrkit/util/data_dir.h"
#include "pbrkit/util/error.h"

namespace pbrkit {

glm::vec3 Environment::eval(glm::vec3 d) const {
  const glm::vec2 uv = equirect_uv(world_to_env(d, rotation_deg));
  // Texel centres at (i + 0.5) / size; u wraps around, v clamps at the poles.
  const float x = uv.x * float(map.width) - 0.5f;
  const float y = uv.y * float(map.height) - 0.5f;
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  const float fx = x - float(x0), fy = y - float(y0);
  auto wrap_x = [&](int i) { return ((i % map.width) + map.width) % map.width; };
  auto clamp_y = [&](int j) { return std::clamp(j, 0, map.height - 1); };
  const glm::vec3 c00 = map.rgb(wrap_x(x0), clamp_y(y0));
  const glm::vec3 c10 = map.rgb(wrap_x(x0 + 1), clamp_y(y0));
  const glm::vec3 c01 = map.rgb(wrap_x(x0), clamp_y(y0 + 1));
  const glm::vec3 c11 = map.rgb(wrap_x(x0 + 1), clamp_y(y0 + 1));
  const glm::vec3 c = glm::mix(glm::mix(c00, c10, fx), glm::mix(c01, c11, fx), fy);
  return c * intensity;
}

Environment Environment::load(const std::filesystem::path& path, float rotation_deg,
                              float intensity, bool warn_cleaned) {
  ImageReadOptions options;
  options.warn_cleaned = warn_cleaned;
  options.max_pixels = std::size_t(16384) * 8192;
  Environment env;
  env.map = read_image(path, options);
  if (env.map.width != 2 * env.map.height) {
    fail(
        "{}: an environment map must be equirectangular with a 2:1 aspect ratio, this one is "
        "{}x{}",
        path.string(), env.map.width, env.map.height);
  }
  if (env.map.channels != 3) {
    Image rgb(env.map.width, env.map.height, 3);
    for (int y = 0; y < rgb.height; ++y)
      for (int x = 0; x < rgb.width; ++x) rgb.set_rgb(x, y, env.map.rgb(x, y));
    env.map = std::move(rgb);
  }
  if (!std::isfinite(rotation_deg)) fail("{}: environment rotation must be finite", path.string());
  if (!(intensity >= 0.0f) || !std::isfinite(intensity)) {
    fail("{}: environment intensity must be a finite number >= 0, got {}", path.string(),
         intensity);
  }
  env.rotation_deg = rotation_deg;
  env.intensity = intensity;
  env.source = path.string();
  return env;
}

Environment Environment::constant(glm::vec3 L, int width) {
  Environment env;
  env.map = Image(width, width / 2, 3);
  for (int y = 0; y < env.map.height; ++y)
    for (int x = 0; x < env.map.width; ++x) env.map.set_rgb(x, y, L);
  env.source = "constant";
  return env;
}

std::filesystem::path default_environment_path() {
  return data_dir() / "env" / "city.exr";
}

Environment load_environment_or_default(const std::string& path, float rotation_deg,
                                        float intensity) {
  if (path.empty())
    return Environment::load(default_environment_path(), rotation_deg, intensity, false);
  return Environment::load(path, rotation_deg, intensity);
}

}  // namespace pbrkit
