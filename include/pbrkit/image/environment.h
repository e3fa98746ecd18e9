#pragma once
// Environment lighting from an equirectangular map, with the project's one orientation
// convention (core/equirect.h), a rotation about +Y and an intensity scale. Shared by the
// baker, the path tracer and the OpenGL renderer.
#include <filesystem>
#include <string>

#include <glm/glm.hpp>

#include "pbrkit/image/image.h"

namespace pbrkit {

struct Environment {
  Image map;                  ///< RGB, linear, 2:1 lat-long, row 0 = zenith
  float rotation_deg = 0.0f;  ///< about +Y, counter-clockwise seen from above
  float intensity = 1.0f;     ///< radiance scale
  std::string source;         ///< file path or "constant"

  /// Radiance arriving from world direction `d` (unit): bilinear lookup (u wraps).
  glm::vec3 eval(glm::vec3 d) const;

  /// Loads an .exr/.hdr environment: checks 2:1 aspect (Error otherwise), size limits
  /// (at most 16384 x 8192), and clamps negative/NaN/Inf samples (warning with counts
  /// unless `warn_cleaned` is false).
  static Environment load(const std::filesystem::path& path, float rotation_deg = 0.0f,
                          float intensity = 1.0f, bool warn_cleaned = true);
  /// A uniform environment of radiance `L` (a tiny map), for furnace tests.
  static Environment constant(glm::vec3 L, int width = 8);
};

/// The built-in default environment shipped with pbrkit (data/env/, CC0, see its
/// LICENSE note), used when no --env is given.
std::filesystem::path default_environment_path();

/// Resolves a user's --env value: a path, or empty for the default environment (whose
/// 342 negative DWAB-ringing samples are clamped without a warning: data/env/LICENSE.md).
Environment load_environment_or_default(const std::string& path, float rotation_deg,
                                        float intensity);

}  // namespace pbrkit
