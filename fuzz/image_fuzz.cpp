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
  // 512 x 512: large enough for every seed, small enough that a header claiming a big
  // image (allocated and zero-filled under ASan) does not dominate the execution rate.
  options.max_pixels = std::size_t(1) << 18;
  try {
    pbrkit::decode_image(data, size, "fuzz-input", options);
  } catch (const pbrkit::Error&) {
  }
  return 0;
}
