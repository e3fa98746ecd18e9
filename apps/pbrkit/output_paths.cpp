#include "output_paths.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "pbrkit/util/error.h"

namespace pbrkit::cli {

ImageOutputs image_outputs(const std::string& output, std::string_view flag) {
  namespace fs = std::filesystem;
  std::string ext = fs::path(output).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (ext != ".png" && ext != ".exr")
    fail("{} {}: the output must end in .png or .exr (pbrkit writes both, the other beside it)",
         flag, output);
  const bool png = ext == ".png";
  const std::string other = fs::path(output).replace_extension(png ? ".exr" : ".png").string();
  return png ? ImageOutputs{output, other} : ImageOutputs{other, output};
}

void create_output_directory(const ImageOutputs& outputs) {
  const std::filesystem::path parent = std::filesystem::path(outputs.png).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
}

}  // namespace pbrkit::cli
