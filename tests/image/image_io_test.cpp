// Image I/O: round trips per format at the precision each format promises, the input
// policy (negative/NaN/Inf -> 0, counted, one warning), DWAB decoding of a real HDRI, and
// clean errors for bad input and failed writes.
#include <gtest/gtest.h>

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>

#include "pbrkit/core/color.h"
#include "pbrkit/image/environment.h"
#include "pbrkit/image/image_io.h"
#include "pbrkit/util/error.h"
#include "pbrkit/util/log.h"
#include "support/test_paths.h"

namespace pbrkit {
namespace {

namespace fs = std::filesystem;

Image random_image(int w, int h, int c, float lo, float hi, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> dist(lo, hi);
  Image img(w, h, c);
  for (float& v : img.data) v = dist(rng);
  return img;
}

std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void write_raw(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// Captures warnings for the lifetime of the object.
struct WarningCapture {
  std::vector<std::string> warnings;
  LogSink previous;
  WarningCapture() {
    previous = set_log_sink([this](LogLevel level, const std::string& m) {
      if (level == LogLevel::kWarning) warnings.push_back(m);
    });
  }
  ~WarningCapture() { set_log_sink(previous); }
};

template <typename F>
std::string expect_error(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected pbrkit::Error";
  return {};
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

TEST(ImageIo, ExrFloatRoundTripIsBitExact) {
  const fs::path dir = test::scratch_dir();
  for (int c : {1, 3, 4}) {
    Image img = random_image(17, 9, c, 0.0f, 1000.0f, 7 + c);
    img.data[0] = 1e-30f;  // denormal-adjacent and huge values survive a float EXR
    img.data[1] = 3.0e38f;
    const fs::path p = dir / fmt::format("f{}.exr", c);
    write_exr(p, img, ExrPixelType::kFloat);
    const Image back = read_image(p);
    ASSERT_EQ(back.width, 17);
    ASSERT_EQ(back.height, 9);
    ASSERT_EQ(back.channels, c);
    EXPECT_EQ(std::memcmp(back.data.data(), img.data.data(), img.data.size() * sizeof(float)), 0)
        << c << " channels";
  }
}

TEST(ImageIo, ExrHalfRoundTripWithinHalfPrecision) {
  const fs::path p = test::scratch_dir() / "h.exr";
  const Image img = random_image(32, 16, 3, 0.001f, 60000.0f, 3);
  write_exr(p, img, ExrPixelType::kHalf);
  const Image back = read_image(p);
  ASSERT_EQ(back.data.size(), img.data.size());
  for (std::size_t i = 0; i < img.data.size(); ++i) {
    // Round to nearest half: relative error at most 2^-11 for normal halves.
    EXPECT_LE(std::abs(back.data[i] - img.data[i]), img.data[i] * std::ldexp(1.0f, -11)) << i;
    EXPECT_EQ(back.data[i], float(half(img.data[i])));
  }
}

TEST(ImageIo, MultiLayerExrRoundTrip) {
  const fs::path p = test::scratch_dir() / "layers.exr";
  const Image beauty = random_image(8, 4, 3, 0.0f, 10.0f, 1);
  const Image albedo = random_image(8, 4, 3, 0.0f, 1.0f, 2);
  const Image depth = random_image(8, 4, 1, 0.0f, 100.0f, 3);
  const Image normal = random_image(8, 4, 3, 0.0f, 1.0f, 4);
  write_exr_layers(p, {{"", {"R", "G", "B"}, &beauty, ExrPixelType::kFloat},
                       {"albedo", {"R", "G", "B"}, &albedo, ExrPixelType::kHalf},
                       {"depth", {"Z"}, &depth, ExrPixelType::kFloat},
                       {"normal", {"X", "Y", "Z"}, &normal, ExrPixelType::kFloat}});
  // The file really has the named channels.
  {
    Imf::InputFile file(p.c_str());
    for (const char* c : {"R", "G", "B", "albedo.R", "albedo.B", "depth.Z", "normal.X"})
      EXPECT_NE(file.header().channels().findChannel(c), nullptr) << c;
    EXPECT_EQ(file.header().channels().findChannel("albedo.R")->type, Imf::HALF);
    EXPECT_EQ(file.header().compression(), Imf::ZIP_COMPRESSION);
  }
  const auto layers = read_exr_layers(p);
  ASSERT_EQ(layers.size(), 4u);
  std::map<std::string, Image> by_name(layers.begin(), layers.end());
  EXPECT_EQ(by_name.at("").data, beauty.data);
  EXPECT_EQ(by_name.at("depth").data, depth.data);
  EXPECT_EQ(by_name.at("normal").data, normal.data);  // X, Y, Z in that order
  const Image& a = by_name.at("albedo");
  ASSERT_EQ(a.channels, 3);
  for (std::size_t i = 0; i < a.data.size(); ++i) EXPECT_EQ(a.data[i], float(half(albedo.data[i])));
  // read_image reads the main layer.
  EXPECT_EQ(read_image(p).data, beauty.data);
  // Layers of different sizes are refused, naming the layer.
  const Image small(4, 4, 3);
  const std::string msg = expect_error([&] {
    write_exr_layers(p, {{"", {"R", "G", "B"}, &beauty, ExrPixelType::kHalf},
                         {"bad", {"R", "G", "B"}, &small, ExrPixelType::kHalf}});
  });
  EXPECT_TRUE(contains(msg, "bad")) << msg;
}

TEST(ImageIo, HdrRoundTripWithinRgbePrecision) {
  const fs::path p = test::scratch_dir() / "x.hdr";
  const Image img = random_image(20, 10, 3, 0.01f, 500.0f, 5);
  write_hdr(p, img);
  const Image back = read_image(p);
  ASSERT_EQ(back.channels, 3);
  ASSERT_EQ(back.width, 20);
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 20; ++x) {
      // RGBE: 8-bit mantissas under a shared exponent -> error below max(rgb) / 128.
      const glm::vec3 a = img.rgb(x, y), b = back.rgb(x, y);
      const float m = std::max({a.x, a.y, a.z});
      for (int c = 0; c < 3; ++c) EXPECT_LE(std::abs(a[c] - b[c]), m / 128.0f);
    }
}

TEST(ImageIo, Png8And16BitRoundTripQuantiseExactly) {
  const fs::path dir = test::scratch_dir();
  for (int bits : {8, 16}) {
    const int levels = bits == 8 ? 255 : 65535;
    Image img(64, 4, 4);
    std::vector<int> expected(img.data.size());
    std::mt19937 rng(bits);
    std::uniform_int_distribution<int> code(0, levels);
    for (std::size_t i = 0; i < img.data.size(); ++i) {
      const int k = code(rng);
      // Off-grid values round to the nearest code; out-of-range ones clamp.
      const float frac = (i % 3 == 0) ? 0.0f : (i % 3 == 1 ? 0.49f : -0.49f);
      img.data[i] = (k + frac) / float(levels);
      expected[i] = k;
    }
    img.data[0] = -0.5f;
    expected[0] = 0;
    img.data[1] = 7.0f;
    expected[1] = levels;
    const fs::path p = dir / fmt::format("q{}.png", bits);
    write_png(p, img, bits);
    ImageReadOptions raw;
    raw.decode_srgb = false;
    ImageReadReport report;
    const Image back = read_image(p, raw, &report);
    ASSERT_EQ(back.channels, 4);
    EXPECT_FALSE(report.srgb_decoded);
    for (std::size_t i = 0; i < img.data.size(); ++i)
      ASSERT_EQ(back.data[i], expected[i] / float(levels)) << bits << " bits, sample " << i;
    // With sRGB decoding the colour channels are decoded and alpha is not.
    const Image lin = read_image(p, {}, &report);
    EXPECT_TRUE(report.srgb_decoded);
    for (std::size_t i = 0; i < 64; ++i) {
      const float v = expected[i] / float(levels);
      EXPECT_NEAR(lin.data[i], i % 4 == 3 ? v : srgb_decode(v), 1e-7f) << i;
    }
  }
}

TEST(ImageIo, JpegDecodesAndIsSrgbDecoded) {
  const fs::path p = test::scratch_dir() / "flat.jpg";
  std::vector<unsigned char> rgb(16 * 16 * 3);
  for (std::size_t i = 0; i < rgb.size(); i += 3) {
    rgb[i] = 200;
    rgb[i + 1] = 100;
    rgb[i + 2] = 50;
  }
  ASSERT_TRUE(stbi_write_jpg(p.c_str(), 16, 16, 3, rgb.data(), 100));
  const Image img = read_image(p);
  ASSERT_EQ(img.width, 16);
  ASSERT_EQ(img.channels, 3);
  // A flat block survives JPEG at quality 100 to within a couple of codes.
  const glm::vec3 c = img.rgb(8, 8);
  EXPECT_NEAR(c.r, srgb_decode(200 / 255.0f), 0.01f);
  EXPECT_NEAR(c.g, srgb_decode(100 / 255.0f), 0.01f);
  EXPECT_NEAR(c.b, srgb_decode(50 / 255.0f), 0.01f);
}

TEST(ImageIo, DecodeFromMemoryReproducesTheWrittenImage) {
  // decode_image (embedded glTF images) on a file's bytes must give back what was written,
  // at each format's precision: PNG to half an 8-bit code (without sRGB decoding), half EXR
  // exactly as float(half(x)), RGBE to max(rgb) / 128.
  const fs::path dir = test::scratch_dir();
  const Image img = random_image(5, 3, 3, 0.0f, 1.0f, 9);
  ImageReadOptions raw;
  raw.decode_srgb = false;
  for (const char* name : {"m.png", "m.exr", "m.hdr"}) {
    const fs::path p = dir / name;
    if (p.extension() == ".png") write_png(p, img);
    if (p.extension() == ".exr") write_exr(p, img);
    if (p.extension() == ".hdr") write_hdr(p, img);
    const std::string bytes = read_bytes(p);
    const Image a = decode_image(bytes.data(), bytes.size(), "embedded image 0", raw);
    ASSERT_EQ(a.width, img.width) << name;
    ASSERT_EQ(a.height, img.height) << name;
    ASSERT_EQ(a.channels, 3) << name;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        const glm::vec3 want = img.rgb(x, y), got = a.rgb(x, y);
        for (int c = 0; c < 3; ++c) {
          if (p.extension() == ".png") {
            EXPECT_NEAR(got[c], want[c], 0.5f / 255.0f + 1e-6f) << name;
          } else if (p.extension() == ".exr") {
            EXPECT_EQ(got[c], float(half(want[c]))) << name;
          } else {
            EXPECT_LE(std::abs(got[c] - want[c]), std::max({want.x, want.y, want.z}) / 128.0f)
                << name;
          }
        }
      }
  }
}

// Writes an EXR with OpenEXR directly (float RGB) from given samples.
void write_raw_exr(const fs::path& p, int w, int h, std::vector<float> rgb) {
  Imf::Header header(w, h);
  for (const char* c : {"R", "G", "B"}) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
  Imf::FrameBuffer fb;
  const char* names[] = {"R", "G", "B"};
  for (int c = 0; c < 3; ++c)
    fb.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(rgb.data() + c),
                                   3 * sizeof(float), 3 * sizeof(float) * w));
  Imf::OutputFile file(p.c_str(), header);
  file.setFrameBuffer(fb);
  file.writePixels(h);
}

TEST(ImageIo, NegativeNanInfAreZeroedCountedAndWarnedOnce) {
  const fs::path p = test::scratch_dir() / "bad_values.exr";
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  write_raw_exr(p, 3, 2,
                {1.0f, -2.0f, nan,    //
                 inf, 0.5f, -inf,     //
                 -0.001f, nan, 2.0f,  //
                 0.0f, 3.0f, 4.0f,    //
                 nan, -1.0f, 7.0f,    //
                 5.0f, 6.0f, inf});
  WarningCapture capture;
  ImageReadReport report;
  const Image img = read_image(p, {}, &report);
  EXPECT_EQ(report.negative, 3u);
  EXPECT_EQ(report.nan, 3u);
  EXPECT_EQ(report.inf, 3u);  // +inf twice, -inf once
  const std::vector<float> want = {1, 0, 0, 0, 0.5f, 0, 0, 0, 2, 0, 3, 4, 0, 0, 7, 5, 6, 0};
  EXPECT_EQ(img.data, want);
  ASSERT_EQ(capture.warnings.size(), 1u);
  const std::string& w = capture.warnings[0];
  EXPECT_TRUE(contains(w, p.string())) << w;
  EXPECT_TRUE(contains(w, "3 negative")) << w;
  EXPECT_TRUE(contains(w, "3 NaN")) << w;
  EXPECT_TRUE(contains(w, "3 infinite")) << w;
  // A clean file gives no warning.
  capture.warnings.clear();
  write_raw_exr(p, 1, 1, {1, 2, 3});
  read_image(p);
  EXPECT_TRUE(capture.warnings.empty());
}

TEST(ImageIo, ReadsDwabHdriAndClampsItsNegativeSamples) {
  const fs::path p = test::test_data("images/night.exr");
  // Independent count: decode the raw halves with OpenEXR itself.
  std::size_t raw_negative = 0, raw_nan = 0;
  float raw_max_r = 0.0f;
  {
    Imf::InputFile file(p.c_str());
    EXPECT_EQ(file.header().compression(), Imf::DWAB_COMPRESSION);
    const Imath::Box2i dw = file.header().dataWindow();
    const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
    std::vector<half> px(std::size_t(w) * h * 3);
    Imf::FrameBuffer fb;
    const char* names[] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c)
      fb.insert(names[c], Imf::Slice(Imf::HALF, reinterpret_cast<char*>(px.data() + c),
                                     3 * sizeof(half), 3 * sizeof(half) * w));
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    for (std::size_t i = 0; i < px.size(); ++i) {
      raw_negative += px[i] < 0.0f;
      raw_nan += px[i].isNan();
      if (i % 3 == 0) raw_max_r = std::max(raw_max_r, float(px[i]));
    }
  }
  EXPECT_GT(raw_negative, 0u);
  EXPECT_EQ(raw_nan, 0u);
  WarningCapture capture;
  ImageReadReport report;
  const Image img = read_image(p, {}, &report);
  EXPECT_EQ(img.width, 512);
  EXPECT_EQ(img.height, 256);
  EXPECT_EQ(img.channels, 3);
  EXPECT_EQ(report.negative, raw_negative);
  EXPECT_EQ(report.nan, 0u);
  EXPECT_EQ(report.inf, 0u);
  EXPECT_EQ(capture.warnings.size(), 1u);
  float max_y = 0.0f, max_r = 0.0f;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const glm::vec3 c = img.rgb(x, y);
      for (int i = 0; i < 3; ++i) {
        ASSERT_FALSE(std::isnan(c[i]));
        ASSERT_GE(c[i], 0.0f);
      }
      max_y = std::max(max_y, luminance(c));
      max_r = std::max(max_r, c.r);
    }
  EXPECT_EQ(max_r, raw_max_r);
  EXPECT_EQ(max_r, 24.765625f);  // oiiotool --stats: max R = 24.765625
  // tests/data/assets/README.md (measured with OpenImageIO): max luminance 15.49.
  EXPECT_NEAR(max_y, 15.49f, 0.01f);
}

// The shipped default environment has a few negative DWAB-ringing samples (documented in
// data/env/LICENSE.md): clamped like any file's, but without a warning on every render
// that uses the default; a user's file with the same samples still gets the warning.
TEST(ImageIo, DefaultEnvironmentIsCleanedWithoutAWarning) {
  WarningCapture capture;
  const Environment quiet = load_environment_or_default("", 0.0f, 1.0f);
  EXPECT_TRUE(capture.warnings.empty());
  const Environment loud = Environment::load(default_environment_path());
  ASSERT_EQ(capture.warnings.size(), 1u);
  EXPECT_TRUE(contains(capture.warnings[0], "negative")) << capture.warnings[0];
  EXPECT_EQ(quiet.map.data, loud.map.data);
  EXPECT_GE(*std::min_element(quiet.map.data.begin(), quiet.map.data.end()), 0.0f);
}

TEST(ImageIo, BadInputGivesErrorsNamingTheFile) {
  const fs::path dir = test::scratch_dir();
  std::string msg = expect_error([&] { read_image(dir / "missing.exr"); });
  EXPECT_TRUE(contains(msg, "missing.exr") && contains(msg, "not found")) << msg;

  write_raw(dir / "garbage.png", "this is not an image at all, just some text.");
  msg = expect_error([&] { read_image(dir / "garbage.png"); });
  EXPECT_TRUE(contains(msg, "garbage.png") && contains(msg, "unknown image format")) << msg;

  write_raw(dir / "empty.exr", "");
  msg = expect_error([&] { read_image(dir / "empty.exr"); });
  EXPECT_TRUE(contains(msg, "empty.exr")) << msg;

  msg = expect_error([&] { read_image(dir); });
  EXPECT_TRUE(contains(msg, "directory")) << msg;

  // Truncated files of every format: magic bytes right, content cut short.
  const Image img = random_image(64, 64, 3, 0.0f, 1.0f, 11);
  write_exr(dir / "full.exr", img);
  write_png(dir / "full.png", img);
  write_hdr(dir / "full.hdr", img);
  for (const char* name : {"full.exr", "full.png", "full.hdr"}) {
    const std::string bytes = read_bytes(dir / name);
    for (double keep : {0.5, 0.1}) {
      const fs::path cut = dir / (std::string("cut_") + name);
      write_raw(cut, bytes.substr(0, std::size_t(bytes.size() * keep)));
      msg = expect_error([&] { read_image(cut); });
      EXPECT_TRUE(contains(msg, cut.string())) << msg;
    }
    // Header only (first 12 bytes).
    write_raw(dir / "head", bytes.substr(0, 12));
    msg = expect_error([&] { read_image(dir / "head"); });
    EXPECT_TRUE(contains(msg, "head")) << msg;
  }

  // Over the pixel limit.
  ImageReadOptions small;
  small.max_pixels = 1000;
  msg = expect_error([&] { read_image(dir / "full.png", small); });
  EXPECT_TRUE(contains(msg, "too large") && contains(msg, "1000")) << msg;
  msg = expect_error([&] { read_image(test::test_data("images/night.exr"), small); });
  EXPECT_TRUE(contains(msg, "too large")) << msg;
}

// A scan-line EXR's chunk offset table is trusted by OpenEXR to seek; offsets near 2^64
// made our in-memory stream compute pos + n with wrap-around and read before the buffer
// (found by fuzz_image; ASan reports it). Every absurd offset must give a clean error.
TEST(ImageIo, ExrWithAbsurdChunkOffsetsFailsCleanly) {
  const fs::path dir = test::scratch_dir();
  write_exr(dir / "one_chunk.exr", Image(4, 4, 3, 0.25f));
  const std::string bytes = read_bytes(dir / "one_chunk.exr");
  // One chunk (ZIP holds 16 lines): its 8-byte table entry points just past itself.
  std::size_t table = 0;
  for (std::size_t p = 8; p + 8 <= bytes.size(); ++p) {
    std::uint64_t v;
    std::memcpy(&v, bytes.data() + p, 8);
    if (v == p + 8) table = p;
  }
  ASSERT_NE(table, 0u) << "offset table not found";
  for (std::uint64_t bad : {~std::uint64_t(0), ~std::uint64_t(0) - 3, std::uint64_t(bytes.size()),
                            std::uint64_t(bytes.size()) + 4096}) {
    std::string corrupt = bytes;
    std::memcpy(corrupt.data() + table, &bad, 8);
    try {
      const Image img = decode_image(corrupt.data(), corrupt.size(), "corrupt.exr");
      // OpenEXR may rebuild the table by scanning the chunks; then the pixels are right.
      EXPECT_EQ(img.width, 4);
      EXPECT_FLOAT_EQ(img.data[0], 0.25f);
    } catch (const Error& e) {
      EXPECT_TRUE(contains(e.what(), "corrupt.exr")) << e.what();
    }
  }
}

// OpenEXR's C++ API allocates from the header while opening a file, so a tiny file
// declaring a huge image (a 173-byte input made it allocate 2 GB), a huge attribute or
// thousands of channels must be refused before it sees the file (found by fuzz_image).
TEST(ImageIo, ExrDeclaringHugeSizesIsRefusedBeforeDecoding) {
  const fs::path dir = test::scratch_dir();
  write_exr(dir / "small.exr", Image(4, 4, 3, 0.25f));
  const std::string bytes = read_bytes(dir / "small.exr");
  const std::string key = std::string("dataWindow") + '\0' + "box2i" + '\0';
  const std::size_t at = bytes.find(key);
  ASSERT_NE(at, std::string::npos);
  const std::size_t box = at + key.size() + 4;  // after the int32 size (16)
  ImageReadOptions limit;
  limit.max_pixels = std::size_t(1) << 20;  // the fuzz target's order of magnitude
  for (const auto& [max_x, max_y] :
       {std::pair{16776704, 0}, std::pair{0, 2000000000}, std::pair{70000, 70000}}) {
    std::string huge = bytes;
    std::memcpy(huge.data() + box + 8, &max_x, 4);
    std::memcpy(huge.data() + box + 12, &max_y, 4);
    const std::string msg =
        expect_error([&] { decode_image(huge.data(), huge.size(), "huge.exr", limit); });
    // Refused by our limit, or by OpenEXRCore's own sanity limit on data windows.
    EXPECT_TRUE(contains(msg, "huge.exr") &&
                (contains(msg, "too large") || contains(msg, "Invalid data window")))
        << msg;
  }
  // An attribute whose declared size runs past the end of the file (OpenEXR would allocate
  // it first; a fuzzer input declared 1.7 GB in a 352-byte file).
  {
    std::string cut = bytes;
    const std::int32_t absurd = 1769144412;
    std::memcpy(cut.data() + at + key.size(), &absurd, 4);
    const std::string msg =
        expect_error([&] { decode_image(cut.data(), cut.size(), "cut.exr", limit); });
    EXPECT_TRUE(contains(msg, "cut.exr") && contains(msg, "Invalid size")) << msg;
  }
  // 2000 channels of a 1024 x 1024 image: within the pixel limit, not within its memory.
  {
    const fs::path many = dir / "many.exr";
    Imf::Header header(1024, 1024);
    for (int c = 0; c < 2000; ++c)
      header.channels().insert(std::string("c").append(std::to_string(c)), Imf::Channel(Imf::HALF));
    { Imf::OutputFile out(many.string().c_str(), header); }  // header only: no pixels
    const std::string b = read_bytes(many);
    const std::string msg =
        expect_error([&] { decode_image(b.data(), b.size(), "many.exr", limit); });
    EXPECT_TRUE(contains(msg, "many.exr") && contains(msg, "2000 channels")) << msg;
  }
  // The fuzzer's own input (a corrupt header around the same data window).
  const std::string found = read_bytes(test::test_data("fuzz/image/exr_data_window_16m_wide.exr"));
  const std::string msg =
      expect_error([&] { decode_image(found.data(), found.size(), "fuzz.exr", limit); });
  EXPECT_TRUE(contains(msg, "fuzz.exr")) << msg;
}

// stb_image grows its buffer to an IDAT chunk's declared length before reading it (a
// 98-byte file made it allocate 1.6 GB; found by fuzz_image): chunks must fit the file.
TEST(ImageIo, PngChunkLongerThanTheFileIsRefused) {
  const fs::path dir = test::scratch_dir();
  write_png(dir / "ok.png", Image(4, 4, 3, 0.5f));
  const std::string bytes = read_bytes(dir / "ok.png");
  const std::size_t idat = bytes.find("IDAT");
  ASSERT_NE(idat, std::string::npos);
  std::string bad = bytes;
  const unsigned char huge[4] = {0x60, 0x00, 0x00, 0x00};
  std::memcpy(bad.data() + idat - 4, huge, 4);
  const std::string msg = expect_error([&] { decode_image(bad.data(), bad.size(), "bad.png"); });
  EXPECT_TRUE(contains(msg, "bad.png") && contains(msg, "IDAT") && contains(msg, "past the end"))
      << msg;
  // No IEND: truncated.
  const std::string cut = bytes.substr(0, bytes.find("IEND") - 4);
  const std::string msg2 = expect_error([&] { decode_image(cut.data(), cut.size(), "cut.png"); });
  EXPECT_TRUE(contains(msg2, "cut.png") && contains(msg2, "truncated")) << msg2;
  // The original still decodes.
  EXPECT_EQ(decode_image(bytes.data(), bytes.size(), "ok.png").width, 4);
}

TEST(ImageIo, FailedWritesLeaveNothingBehind) {
  const fs::path dir = test::scratch_dir();
  const Image img(4, 4, 3, 0.5f);
  const fs::path missing = dir / "no_such_dir";
  for (const char* name : {"a.exr", "a.png", "a.hdr"}) {
    const fs::path p = missing / name;
    const std::string msg = expect_error([&] {
      if (p.extension() == ".exr") write_exr(p, img);
      if (p.extension() == ".png") write_png(p, img);
      if (p.extension() == ".hdr") write_hdr(p, img);
    });
    EXPECT_TRUE(contains(msg, name)) << msg;
  }
  EXPECT_FALSE(fs::exists(missing));
  // Refused before writing: bad bit depth, empty image. Nothing appears in the directory.
  expect_error([&] { write_png(dir / "b.png", img, 12); });
  expect_error([&] { write_exr(dir / "e.exr", Image()); });
  expect_error([&] { write_png(dir / "e.png", Image()); });
  EXPECT_TRUE(fs::is_empty(dir));
  // And a successful write leaves exactly the file (no temporary).
  write_png(dir / "ok.png", img);
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    ++files;
    EXPECT_EQ(e.path().filename(), "ok.png");
  }
  EXPECT_EQ(files, 1);
}

}  // namespace
}  // namespace pbrkit
