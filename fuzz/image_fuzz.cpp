// libFuzzer target: image decoding (PNG/JPEG/HDR/EXR by content) from arbitrary bytes.
#include <cstddef>
#include <cstdint>

#include "pbrkit/image/image_io.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/log.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool quiet = [] {
    pbrkit::set_log_sink([](pbrkit::LogLevel, const std::string&) {});
    return true;
  }();
  (void)quiet;
  pbrkit::ImageReadOptions options;
  options.max_pixels = std::size_t(1) << 22;
  try {
    pbrkit::decode_image(data, size, "fuzz-input", options);
  } catch (const pbrkit::Error&) {
  }
  return 0;
}
