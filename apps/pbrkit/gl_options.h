#pragma once
// The OpenGL renderer's option values as the command line spells them (`pbrkit render
// --renderer gl`, `pbrkit view`), parsed into the library's typed settings. The library
// takes only the enums and structs; the flag names in the errors belong here, with the
// command line.
#include <string_view>

#include "pbrkit/gl/renderer.h"

namespace pbrkit::cli {

/// "env", "blur:<mip>" or "color:<r>,<g>,<b>"; Error naming --background otherwise.
gl::Background parse_background(std::string_view text);
/// "sh" | "cube"; Error naming --irradiance otherwise.
gl::IrradianceMode parse_irradiance_mode(std::string_view name);

}  // namespace pbrkit::cli
