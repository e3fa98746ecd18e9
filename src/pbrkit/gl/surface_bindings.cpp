#include "pbrkit/gl/surface_bindings.h"

#include <cctype>

#include <fmt/format.h>

#include "pbrkit/scene/material_schema.h"

namespace pbrkit::gl {

std::string texture_slot_macro(TextureSlot slot) {
  std::string name = texture_slot_name(slot);
  if (const auto dot = name.rfind('.'); dot != std::string::npos) name = name.substr(dot + 1);
  std::string macro;
  for (const char c : name) {
    if (std::isupper(static_cast<unsigned char>(c)) && !macro.empty()) macro += '_';
    macro += char(std::toupper(static_cast<unsigned char>(c)));
  }
  const std::string suffix = "_TEXTURE";
  if (macro.size() < suffix.size() ||
      macro.compare(macro.size() - suffix.size(), suffix.size(), suffix) != 0)
    macro += suffix;
  return macro;
}

std::string factor_uniform(const MaterialFactor& factor) {
  std::string name = std::string("u") + factor.json_name;
  name[1] = char(std::toupper(static_cast<unsigned char>(name[1])));
  return name;
}

std::vector<SurfaceBinding> surface_bindings() {
  std::vector<SurfaceBinding> b;
  for (int t = 0; t < kTextureSlotCount; ++t)
    b.push_back({texture_slot_macro(TextureSlot(t)), texture_unit(TextureSlot(t))});
  b.push_back({"ENERGY_DIRECT", kEnergyDirectUnit});
  b.push_back({"ENERGY_IBL", kEnergyIblUnit});
  b.push_back({"SPECULAR_CUBE", kSpecularCubeUnit});
  b.push_back({"IRRADIANCE_CUBE", kIrradianceCubeUnit});
  b.push_back({"ENERGY_COAT", kCoatEnergyUnit});
  b.push_back({"SHEEN_CUBE", kSheenCubeUnit});
  b.push_back({"SHEEN_LUT", kSheenLutUnit});
  b.push_back({"TRANSMISSION_FRAME", kTransmissionFrameUnit});
  b.push_back({"BACK_POSITION", kBackPositionUnit});
  b.push_back({"BACK_NORMAL", kBackNormalUnit});
  b.push_back({"FRAME_DEPTH", kFrameDepthUnit});
  b.push_back({"ANISOTROPIC_ALBEDO", kAnisotropicAlbedoUnit});
  b.push_back({"ANISOTROPIC_ENERGY", kAnisotropicEnergyUnit});
  b.push_back(
      {"INSTANCE_TRANSFORMS", kInstanceBufferBinding, SurfaceBinding::Kind::kStorageBuffer});
  b.push_back({"PUNCTUAL_LIGHTS", kLightBufferBinding, SurfaceBinding::Kind::kStorageBuffer});
  b.push_back(
      {"LIGHT_CLUSTER_RANGES", kClusterRangeBufferBinding, SurfaceBinding::Kind::kStorageBuffer});
  b.push_back({"LISTED_LIGHTS", kListedLightBufferBinding, SurfaceBinding::Kind::kStorageBuffer});
  b.push_back(
      {"DEFORM_VERTICES", kDeformVertexBufferBinding, SurfaceBinding::Kind::kStorageBuffer});
  b.push_back({"JOINT_MATRICES", kJointMatrixBufferBinding, SurfaceBinding::Kind::kStorageBuffer});
  b.push_back({"MORPH_WEIGHTS", kMorphWeightBufferBinding, SurfaceBinding::Kind::kStorageBuffer});
  b.push_back({"OCCLUDERS", kOccluderBufferBinding, SurfaceBinding::Kind::kUniformBuffer});
  return b;
}

std::vector<SurfaceBinding> background_bindings() {
  return {{"ENVIRONMENT", kBackgroundEnvironmentUnit},
          {"SPECULAR_CUBE", kBackgroundSpecularCubeUnit}};
}

std::vector<SurfaceBinding> display_bindings() {
  return {{"FRAME", kDisplayFrameUnit}};
}

namespace {

std::string binding_defines(const std::vector<SurfaceBinding>& bindings) {
  std::string d;
  for (const SurfaceBinding& b : bindings)
    d += fmt::format("#define BINDING_{} {}\n", b.name, b.point);
  return d;
}

}  // namespace

const std::string& background_prelude() {
  static const std::string prelude = binding_defines(background_bindings());
  return prelude;
}

const std::string& display_prelude() {
  static const std::string prelude = binding_defines(display_bindings());
  return prelude;
}

const std::string& surface_prelude() {
  static const std::string prelude = [] {
    std::string d = fmt::format("#define TEXTURE_SLOT_COUNT {}\n", kTextureSlotCount);
    for (int t = 0; t < kTextureSlotCount; ++t)
      d += fmt::format("#define SLOT_{} {}\n", texture_slot_macro(TextureSlot(t)), t);
    return d + binding_defines(surface_bindings());
  }();
  return prelude;
}

}  // namespace pbrkit::gl
