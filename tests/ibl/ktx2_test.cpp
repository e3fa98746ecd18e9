// KTX 2.0: round trips and the byte layout checked against the specification.
#include "pbrkit/ibl/ktx2.h"

#include <gtest/gtest.h>

#include <cstring>

#include "pbrkit/core/sampling.h"
#include "pbrkit/util/error.h"
#include "support/test_paths.h"

namespace pbrkit {
namespace {

std::uint32_t u32(const std::string& b, std::size_t at) {
  std::uint32_t v;
  std::memcpy(&v, b.data() + at, 4);  // little-endian host (x86-64), as the file
  return v;
}
std::uint64_t u64(const std::string& b, std::size_t at) {
  std::uint64_t v;
  std::memcpy(&v, b.data() + at, 8);
  return v;
}

Cubemap random_cube(int size, int levels, std::uint64_t seed) {
  Pcg32 rng(seed);
  Cubemap cube;
  for (int l = 0; l < levels; ++l) {
    std::array<Image, 6> faces;
    for (Image& f : faces) {
      f = Image(size >> l, size >> l, 4);
      for (float& v : f.data) v = rng.next_float() * 100.0f;
    }
    cube.mips.push_back(faces);
  }
  return cube;
}

TEST(Ktx2, Float32CubemapRoundTripsBitExactly) {
  const Cubemap cube = random_cube(16, 5, 1);
  const auto path = test::scratch_dir() / "cube.ktx2";
  write_ktx2(path, ktx2_from_cubemap(cube, Ktx2Format::kRgba32Float));
  const Cubemap back = cubemap_from_ktx2(read_ktx2(path));
  ASSERT_EQ(back.levels(), 5);
  for (int l = 0; l < 5; ++l)
    for (int f = 0; f < 6; ++f) {
      ASSERT_EQ(back.mips[l][f].width, 16 >> l);
      ASSERT_EQ(std::memcmp(back.mips[l][f].data.data(), cube.mips[l][f].data.data(),
                            cube.mips[l][f].data.size() * sizeof(float)),
                0)
          << l << " " << f;
    }
}

TEST(Ktx2, HalfTexturesRoundTripBitExactlyAndRoundToHalf) {
  const Cubemap cube = random_cube(8, 4, 2);
  const Ktx2Texture t = ktx2_from_cubemap(cube, Ktx2Format::kRgba16Float);
  const std::string bytes = encode_ktx2(t);
  const Ktx2Texture back = decode_ktx2(bytes, "mem");
  ASSERT_EQ(back.levels, t.levels);  // the stored halves, bit for bit
  EXPECT_EQ(encode_ktx2(back), bytes);
  const Cubemap c = cubemap_from_ktx2(back);
  for (int l = 0; l < 4; ++l)
    for (int f = 0; f < 6; ++f)
      for (std::size_t i = 0; i < c.mips[l][f].data.size(); ++i)
        ASSERT_NEAR(c.mips[l][f].data[i], cube.mips[l][f].data[i],
                    cube.mips[l][f].data[i] * 1e-3f);  // half: 11-bit mantissa
}

TEST(Ktx2, HeaderFollowsTheSpecificationLayout) {
  const Cubemap cube = random_cube(8, 3, 3);  // 8, 4, 2 px
  Ktx2Texture t = ktx2_from_cubemap(cube, Ktx2Format::kRgba16Float);
  t.metadata.emplace_back("KTXwriter", "pbrkit test");
  const std::string b = encode_ktx2(t);
  // Section 3.1: the identifier.
  const unsigned char id[12] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
  EXPECT_EQ(std::memcmp(b.data(), id, 12), 0);
  // Section 3.2: the header.
  EXPECT_EQ(u32(b, 12), 97u);  // VK_FORMAT_R16G16B16A16_SFLOAT
  EXPECT_EQ(u32(b, 16), 2u);   // typeSize
  EXPECT_EQ(u32(b, 20), 8u);   // pixelWidth
  EXPECT_EQ(u32(b, 24), 8u);   // pixelHeight
  EXPECT_EQ(u32(b, 28), 0u);   // pixelDepth
  EXPECT_EQ(u32(b, 32), 0u);   // layerCount
  EXPECT_EQ(u32(b, 36), 6u);   // faceCount
  EXPECT_EQ(u32(b, 40), 3u);   // levelCount
  EXPECT_EQ(u32(b, 44), 0u);   // supercompressionScheme
  // Section 3.3: the index; the DFD follows the level index (80 + 3 * 24).
  const std::uint32_t dfd_at = u32(b, 48), dfd_len = u32(b, 52);
  EXPECT_EQ(dfd_at, 80u + 3u * 24u);
  EXPECT_EQ(dfd_len, 92u);
  EXPECT_EQ(u32(b, dfd_at), dfd_len);  // dfdTotalSize
  // Basic descriptor block: Khronos vendor, type 0, version 2, 88 bytes, RGBSDA, BT709,
  // linear, 8 bytes per texel; R sample: offset 0, 16 bits, SIGNED | FLOAT.
  EXPECT_EQ(u32(b, dfd_at + 4), 0u);
  EXPECT_EQ(u32(b, dfd_at + 8), 2u | (88u << 16));
  EXPECT_EQ(u32(b, dfd_at + 12), 0x00010101u);
  EXPECT_EQ(u32(b, dfd_at + 20), 8u);
  EXPECT_EQ(u32(b, dfd_at + 28), (15u << 16) | (0xC0u << 24));
  EXPECT_EQ(u32(b, dfd_at + 28 + 3 * 16), 48u | (15u << 16) | ((0xC0u | 15u) << 24));
  // Key/value data right after the DFD, sorted: KTXorientation "rd" first.
  const std::uint32_t kvd_at = u32(b, 56), kvd_len = u32(b, 60);
  EXPECT_EQ(kvd_at, dfd_at + dfd_len);
  EXPECT_EQ(kvd_len % 4, 0u);
  EXPECT_EQ(u32(b, kvd_at), std::string("KTXorientation").size() + 1 + 3);
  EXPECT_EQ(std::string(b.data() + kvd_at + 4, 18), std::string("KTXorientation\0rd\0", 18));
  EXPECT_EQ(u64(b, 64), 0u);  // no supercompression global data
  EXPECT_EQ(u64(b, 72), 0u);
  // Section 3.9: the level index lists level 0 first; the data is stored smallest first,
  // each level aligned to lcm(8, 4) = 8, with 6 faces of w * h * 8 bytes.
  std::uint64_t prev_offset = ~0ull;
  for (int l = 0; l < 3; ++l) {
    const std::uint64_t offset = u64(b, 80 + 24 * l), length = u64(b, 80 + 24 * l + 8);
    EXPECT_EQ(length, 6u * (8u >> l) * (8u >> l) * 8u);
    EXPECT_EQ(u64(b, 80 + 24 * l + 16), length);
    EXPECT_EQ(offset % 8, 0u);
    EXPECT_LT(offset, prev_offset);  // level 0 is last in the file
    EXPECT_GE(offset, kvd_at + kvd_len);
    prev_offset = offset;
  }
  EXPECT_EQ(u64(b, 80) + u64(b, 88), b.size());
  // +Y face (index 2) of level 0, texel (0, 0), channel R: the half of the input.
  const std::uint64_t face2 = u64(b, 80) + 2 * 8 * 8 * 8;
  std::uint16_t h;
  std::memcpy(&h, b.data() + face2, 2);
  EXPECT_EQ(h, t.levels[0][2 * 8 * 8 * 8] | (t.levels[0][2 * 8 * 8 * 8 + 1] << 8));
  const Ktx2Texture back = decode_ktx2(b, "mem");
  ASSERT_EQ(back.metadata.size(), 2u);
  EXPECT_EQ(back.metadata[0].first, "KTXorientation");
  EXPECT_EQ(back.metadata[0].second, "rd");
  EXPECT_EQ(back.metadata[1].second, "pbrkit test");
}

TEST(Ktx2, TwoDimensionalFloatImage) {
  Image lut(5, 3, 4);
  for (std::size_t i = 0; i < lut.data.size(); ++i) lut.data[i] = float(i) * 0.1f;
  const std::string b = encode_ktx2(ktx2_from_image(lut, Ktx2Format::kRgba32Float));
  EXPECT_EQ(u32(b, 12), 109u);
  EXPECT_EQ(u32(b, 16), 4u);
  EXPECT_EQ(u32(b, 36), 1u);
  EXPECT_EQ(u64(b, 80) % 16, 0u);
  const Image back = image_from_ktx2(decode_ktx2(b, "mem"));
  EXPECT_EQ(back.data, lut.data);
}

TEST(Ktx2, RejectsBadFilesWithTheirName) {
  const std::string good =
      encode_ktx2(ktx2_from_cubemap(random_cube(4, 2, 4), Ktx2Format::kRgba16Float));
  auto expect_error = [](const std::string& bytes, const std::string& fragment) {
    try {
      decode_ktx2(bytes, "bad.ktx2");
      ADD_FAILURE() << "no error for " << fragment;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("bad.ktx2"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  expect_error("hello", "not a KTX 2.0 file");
  expect_error(good.substr(0, good.size() - 10), "outside the file");
  std::string other = good;
  other[12] = 37;  // VK_FORMAT_R8G8B8A8_UNORM
  expect_error(other, "unsupported vkFormat 37");
  std::string super = good;
  super[44] = 1;  // BasisLZ
  expect_error(super, "supercompressed");
  EXPECT_THROW(read_ktx2(test::scratch_dir() / "missing.ktx2"), Error);
}

}  // namespace
}  // namespace pbrkit
