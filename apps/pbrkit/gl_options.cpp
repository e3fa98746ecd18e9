#include "gl_options.h"

#include "numeric_options.h"
#include "pbrkit/util/error.h"

namespace pbrkit::cli {

gl::Background parse_background(std::string_view text) {
  using gl::Background;
  Background b;
  auto parse_float = [&](std::string_view s) {
    return parse_finite_float(s, "--background", text);
  };
  if (text == "env") return b;
  if (text.substr(0, 5) == "blur:") {
    b.mode = Background::Mode::kBlurred;
    b.blur_lod = parse_float(text.substr(5));
    if (b.blur_lod < 0.0f) fail("--background: the blur mip must be >= 0, got '{}'", text);
    return b;
  }
  if (text.substr(0, 6) == "color:") {
    b.mode = Background::Mode::kColor;
    std::string_view rest = text.substr(6);
    for (int i = 0; i < 3; ++i) {
      const std::size_t comma = rest.find(',');
      if ((i < 2) != (comma != std::string_view::npos))
        fail("--background: expected color:<r>,<g>,<b>, got '{}'", text);
      b.color[i] = parse_float(rest.substr(0, comma));
      rest = comma == std::string_view::npos ? std::string_view() : rest.substr(comma + 1);
    }
    return b;
  }
  fail("--background: expected env, blur:<mip> or color:<r>,<g>,<b>, got '{}'", text);
}

gl::IrradianceMode parse_irradiance_mode(std::string_view name) {
  if (name == "sh") return gl::IrradianceMode::kSH;
  if (name == "cube") return gl::IrradianceMode::kCube;
  fail("--irradiance: expected 'sh' or 'cube', got '{}'", name);
}

}  // namespace pbrkit::cli
