#include "pbrkit/image/output_paths.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include <fmt/format.h>

#include "pbrkit/util/error.h"

namespace pbrkit {

ImageOutputPaths image_output_paths(const std::string& path, std::string_view what) {
  namespace fs = std::filesystem;
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (ext != ".png" && ext != ".exr")
    fail("{} {}: the output must end in .png or .exr (pbrkit writes both, the other beside it)",
         what, path);
  const bool png = ext == ".png";
  const std::string other = fs::path(path).replace_extension(png ? ".exr" : ".png").string();
  return png ? ImageOutputPaths{path, other} : ImageOutputPaths{other, path};
}

ImageOutputPaths frame_output_paths(const ImageOutputPaths& base, int frame) {
  auto numbered = [frame](const std::string& path) {
    std::filesystem::path p(path);
    const std::string ext = p.extension().string();
    return p.replace_filename(p.stem().string() + fmt::format("_{:04d}", frame) + ext).string();
  };
  return {numbered(base.png), numbered(base.exr)};
}

void create_output_directory(const ImageOutputPaths& outputs) {
  const std::filesystem::path parent = std::filesystem::path(outputs.png).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
}

}  // namespace pbrkit
