#include "pbrkit/gl/shader_permutations.h"

namespace pbrkit::gl {

// Whether `m` on a mesh (closed or not) reads the opaque frame (KHR_materials_transmission),
// and the transmission features it compiles in. A volume is only a volume on a closed mesh
// with a thickness (KHR_materials_volume: thickness 0 is thin walled); dispersion changes
// only the refraction through a volume (KHR_materials_dispersion).
void set_transmission_features(const Material& m, bool closed, SurfaceFeatures& f) {
  f.transmission = m.transmission.has_value() && m.transmission->factor > 0.0f;
  f.diffuse_transmission =
      m.diffuse_transmission.has_value() && m.diffuse_transmission->factor > 0.0f;
  f.volume = (f.transmission || f.diffuse_transmission) && closed && m.volume.has_value() &&
             m.volume->thickness_factor > 0.0f;
  f.dispersion =
      f.transmission && f.volume && m.dispersion.has_value() && m.dispersion->dispersion > 0.0f;
}

ShaderPermutations::ShaderPermutations() {
  // The default surface program is compiled up front, so that a driver without GL 4.5
  // features fails here with the compile log rather than at the first frame.
  surface(SurfaceFeatures{});
  for (int mode = 0; mode < 3; ++mode)
    background_[std::size_t(mode)] =
        Program::graphics("background_vertex.glsl", "background_fragment.glsl",
                          background_prelude() + fmt::format("#define MODE {}\n", mode));
}

const Program& ShaderPermutations::surface(const SurfaceFeatures& f) {
  auto it = surface_.find(f.key());
  if (it == surface_.end()) {
    const bool occluders = f.sphere_occluders + f.box_occluders > 0;
    it = surface_
             .emplace(f.key(),
                      Program::graphics("pbr_vertex.glsl", "pbr_fragment.glsl",
                                        f.defines() + (occluders ? occluder_geometry_ : "")))
             .first;
  }
  return it->second;
}

void ShaderPermutations::set_occluder_geometry(std::string define) {
  if (define == occluder_geometry_) return;
  occluder_geometry_ = std::move(define);
  std::erase_if(surface_,
                [](const auto& entry) { return SurfaceFeatures::occluder_bits(entry.first) != 0; });
}

const Program& ShaderPermutations::display(ToneMapper mapper) {
  Program& p = display_[std::size_t(mapper)];
  if (!p.id())
    p = Program::graphics("display_vertex.glsl", "display_fragment.glsl",
                          display_prelude() + fmt::format("#define TONE_MAPPER {}\n", int(mapper)));
  return p;
}

}  // namespace pbrkit::gl
