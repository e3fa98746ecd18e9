#include "pbrkit/gl/ibl_maps.h"

#include <algorithm>
#include <utility>

namespace pbrkit::gl {

IblMaps ibl_maps_from_bake(BakeResult bake, const Environment& env) {
  IblMaps maps;
  maps.specular = std::move(bake.specular);
  maps.irradiance = std::move(bake.irradiance);
  maps.sheen = std::move(bake.sheen);
  maps.sh = bake.sh;
  maps.rotation_deg = env.rotation_deg;
  maps.intensity = env.intensity;
  return maps;
}

BakeOptions realtime_bake_options(int face_size, int samples) {
  BakeOptions bake;
  bake.face_size = face_size;
  bake.min_face_size = std::min(8, face_size);
  bake.samples = samples;
  bake.irradiance_size = 16;
  bake.lut_size = 32;
  bake.quadrature_budget = 0x1p30;
  return bake;
}

}  // namespace pbrkit::gl
