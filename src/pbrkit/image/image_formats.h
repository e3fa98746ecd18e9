#pragma once
// Private to image/: what the per-format files of image_io.h share (format detection by
// content, the size limit, reading a file, the cleaning warning) and each format's decoder:
// image_io.cpp dispatches, exr_io.cpp holds OpenEXR, stb_io.cpp PNG, JPEG and Radiance HDR
// through stb_image, png_write.cpp the libpng writer.
#include <cstddef>
#include <filesystem>
#include <string>

#include "pbrkit/image/image.h"
#include "pbrkit/image/image_io.h"

namespace pbrkit::image_detail {

enum class Format { kExr, kPng, kJpeg, kHdr, kUnknown };

/// Recognises a format by its magic bytes.
Format detect_format(const unsigned char* b, std::size_t n);
/// Error naming `name` when w x h is empty or above options.max_pixels.
void check_size(const std::string& name, long long w, long long h, const ImageReadOptions& options);
/// The whole file; Error naming it when missing, a directory or unreadable.
std::string read_file_bytes(const std::filesystem::path& path);
/// Warns (naming `name`) when sanitize_image changed samples.
void warn_if_cleaned(const std::string& name, const ImageReadReport& r);

/// OpenEXR (exr_io.cpp): the RGB(A), grey or first layer of the file, as float.
Image decode_exr(const unsigned char* bytes, std::size_t size, const std::string& name,
                 const ImageReadOptions& options);
/// PNG, JPEG and Radiance HDR through stb_image (stb_io.cpp), sRGB-decoded per options.
Image decode_stb(const unsigned char* bytes, std::size_t size, const std::string& name,
                 Format format, const ImageReadOptions& options, ImageReadReport& report);

}  // namespace pbrkit::image_detail
