// libFuzzer target: glTF/GLB loading from arbitrary bytes. Any pbrkit::Error is a correct
// rejection; a crash, a sanitizer report, a hang or an exception of another type is a bug.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "pbrkit/scene/gltf/load_gltf.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/log.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool quiet = [] {
    pbrkit::set_log_sink([](pbrkit::LogLevel, const std::string&) {});
    return true;
  }();
  (void)quiet;
  // Small limits keep each input cheap (libFuzzer's default RSS limit is 2 GB).
  pbrkit::LoadOptions options;
  options.limits.max_image_pixels = std::size_t(1) << 20;
  options.limits.max_total_texture_bytes = std::size_t(256) << 20;
  options.limits.max_buffer_bytes = std::size_t(64) << 20;
  options.limits.max_triangles = std::size_t(1) << 20;
  // URIs resolve below a folder that does not exist, so only data: URIs and the GLB
  // buffer can supply bytes.
  const std::filesystem::path name = "/nonexistent-pbrkit-fuzz/input.gltf";
  try {
    pbrkit::load_gltf_from_memory(std::string(reinterpret_cast<const char*>(data), size), name,
                                  options);
  } catch (const pbrkit::Error&) {
  }
  return 0;
}
