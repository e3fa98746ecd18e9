#include "pbrkit/gl/shader_permutations.h"

#include <fmt/format.h>

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

std::vector<SurfaceDefine> SurfaceFeatures::define_list() const {
  const bool occluders = ibl && sphere_occluders + box_occluders > 0;
  std::vector<SurfaceDefine> d = {
      // The KHR_materials_* extensions the material uses, each computed as the path tracer's
      // shade_inputs (pt/shading.cpp) computes it (material_inputs.glsl, one function each).
      {"MATERIAL_SPECULAR", int(specular),
       "KHR_materials_ior and _specular: the dielectric's ior, specular and specular colour"},
      {"MATERIAL_ANISOTROPY", int(anisotropy),
       "KHR_materials_anisotropy: the stretched GGX lobe, its IBL taps (anisotropy_ibl.glsl)"},
      {"MATERIAL_IRIDESCENCE", int(iridescence),
       "KHR_materials_iridescence: the thin-film Fresnel (iridescence.glsl; BRDF_IRIDESCENCE)"},
      {"MATERIAL_CLEARCOAT", int(clearcoat), "KHR_materials_clearcoat: the coat (bsdf.glsl)"},
      {"MATERIAL_SHEEN", int(sheen), "KHR_materials_sheen: the Charlie lobe (sheen.glsl)"},
      {"MATERIAL_UNLIT", int(unlit),
       "KHR_materials_unlit: the base colour as is, from every direction"},
      // The transmission extensions (transmission.glsl).
      {"MATERIAL_TRANSMISSION", int(transmission),
       "KHR_materials_transmission: the opaque frame (uTransmissionFrame) read through the "
       "surface"},
      {"MATERIAL_VOLUME", int(volume),
       "KHR_materials_volume, a thickness > 0 on a closed mesh: refraction through the medium, "
       "Beer-Lambert attenuation; with MATERIAL_TRANSMISSION through both interfaces "
       "(thick_refraction.glsl) where renderer.cpp has drawn the object's back faces"},
      {"MATERIAL_DISPERSION", int(dispersion),
       "KHR_materials_dispersion: three iors for the refraction through a volume"},
      {"MATERIAL_DIFFUSE_TRANSMISSION", int(diffuse_transmission),
       "KHR_materials_diffuse_transmission: the irradiance at -n through the diffuse lobe"},
  };
  for (int t = 0; t < kTextureSlotCount; ++t)
    d.push_back({"HAS_" + texture_slot_macro(TextureSlot(t)), int((textures >> t) & 1u),
                 "the material's texture in this slot (scene.h's TextureSlot) is bound and "
                 "sampled (material_inputs.glsl)"});
  const std::vector<SurfaceDefine> rest = {
      {"HAS_COLOR_0", int(colors),
       "the mesh has COLOR_0 (without it a varying fewer: llvmpipe sets up and interpolates "
       "every varying of every small triangle)"},
      {"ALPHA_MODE", alpha_mode, "glTF's alpha mode: 0 opaque, 1 mask, 2 blend"},
      {"DEFORM", deform,
       "the vertices deform in the vertex shader (deformation.glsl): 0 drawn as uploaded, 1 "
       "morphed then skinned from the mesh's rest data (scene/pose.h's DeformingMesh) at the "
       "pose's weights and joint matrices, 2 the same with flat normals from each deformed "
       "triangle's three corners"},
      {"IBL", int(ibl),
       "1: the environment's split-sum light (surface_light_indirect.glsl, ibl.glsl)"},
      {"IRRADIANCE_SH", int(irradiance_sh),
       "the diffuse irradiance: 1 the environment's nine SH terms, 0 the irradiance cube"},
      {"MULTISCATTER", int(multiscatter),
       "1: multiple-scattering energy compensation (Kulla-Conty 2017, Fdez-Aguera 2019)"},
      {"GEOMETRY", geometry, "the punctual lights' Smith G (brdf.glsl; GeometryModel)"},
      {"FRESNEL", fresnel, "0 Schlick, 1 the spherical-Gaussian form (brdf.glsl)"},
      {"LIGHTS", lights,
       "the punctual lights (surface_light_punctual.glsl): 0 none, 1 every light for every "
       "fragment, 2 the fragment's cluster's (light_clusters.h, Olsson et al. 2012), 3 the "
       "same with spot lights among them"},
      {"LIGHT_COUNT", light_count,
       "with LIGHTS 1, the number of lights compiled in (the loop unrolls over constant "
       "indices; -1: the shader reads uLightCount)"},
      {"DEBUG_CHANNEL", debug_channel,
       "what the surface writes (debug_channels.glsl; DebugChannel's value, 0 the image)"},
      {"IBL_OCCLUDERS", int(occluders),
       "with IBL, the environment light is shadowed by the objects' proxies (occluders.glsl)"},
      {"OCCLUDER_SPHERES", sphere_occluders,
       "the sphere proxies compiled in (their geometry: occluders.h's "
       "occluder_geometry_define, appended after these)"},
      {"OCCLUDER_BOXES", box_occluders, "the parallelepiped proxies compiled in"},
      {"OCCLUDER_BOUNCE", int(ibl && occluder_bounce),
       "with IBL, the opaque proxies send back their own light (occluders.glsl)"},
      {"GLASS_REFLECTIONS", int(glass_reflections),
       "a thick transmissive surface's specular reflection reads the opaque frame where the "
       "mirror direction meets it on the screen (thick_refraction.glsl's reflected_frame)"},
  };
  d.insert(d.end(), rest.begin(), rest.end());
  return d;
}

std::string SurfaceFeatures::defines() const {
  std::string text = surface_prelude();
  for (const SurfaceDefine& d : define_list())
    text += fmt::format("#define {} {}\n", d.name, d.value);
  return text;
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
