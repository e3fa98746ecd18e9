#pragma once
// Writing a bake to a directory (what `pbrkit bake` produces): KTX2 cubemaps and LUTs,
// EXR crosses, tone-mapped PNG previews and manifest.json. All or nothing: files are
// staged in a temporary folder inside the output directory and moved into place only
// once every one of them has been written.
#include <filesystem>
#include <string>
#include <vector>

#include "pbrkit/core/color.h"
#include "pbrkit/ibl/bake.h"
#include "pbrkit/ibl/prefilter_validation.h"
#include "pbrkit/image/display.h"
#include "pbrkit/image/environment.h"

namespace pbrkit {

/// Faces in a horizontal cross, 4 x 3 faces, unused cells black (alpha 0 when RGBA):
///            [+Y]
///      [-X]  [+Z]  [+X]  [-Z]
///            [-Y]
/// Faces are placed as stored (GL convention, no flips): the cross is the cube unfolded
/// and seen from OUTSIDE, continuous across every edge (a mirror image of the view from
/// inside).
Image cube_cross(const std::array<Image, 6>& faces);

/// Which files write_bake_outputs() writes, and how.
struct BakeOutputOptions {
  bool float32 = false;     ///< cubemaps as RGBA32F KTX2 (default RGBA16F)
  bool exr = true;          ///< EXR crosses of every specular level and the irradiance
  bool previews = true;     ///< tone-mapped PNG crosses
  DisplaySettings preview;  ///< exposure and tone mapper of the PNG previews
};

/// Everything the manifest records besides the result itself.
struct BakeRecord {
  const Environment* environment = nullptr;  ///< the baked environment (required)
  BakeOptions options;                       ///< the options it was baked with
  Image lut_reference, lut_classic;          ///< both models' LUTs
  double lut_both_s = 0.0;                   ///< time for both LUTs
  std::vector<PrefilterError> validation;    ///< validate_prefilter()'s table; empty if not run
};

/// Checks that `dir` can be created and written; throws pbrkit::Error naming it otherwise.
void check_output_directory(const std::filesystem::path& dir);

/// Writes every output into `dir` (see the file's comment); returns the file names.
std::vector<std::string> write_bake_outputs(const std::filesystem::path& dir,
                                            const BakeResult& result, const BakeRecord& record,
                                            const BakeOutputOptions& options);

}  // namespace pbrkit
