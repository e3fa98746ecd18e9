// The surface program's #defines (shader_permutations.h's SurfaceFeatures::define_list()):
// the one list that writes and documents them, so each is named once, says what it selects,
// and is read by the shaders it is written for.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "pbrkit/gl/shader_permutations.h"
#include "pbrkit/gl/shaders.h"

namespace pbrkit::gl {
namespace {

TEST(GlShaderPermutations, EveryDefineIsNamedOnceAndDocumented) {
  SurfaceFeatures f;
  std::set<std::string> names;
  const std::string text = f.defines();
  for (const SurfaceDefine& d : f.define_list()) {
    EXPECT_TRUE(names.insert(d.name).second) << d.name << " is written twice";
    EXPECT_GT(std::string(d.meaning).size(), 10u) << d.name << " says nothing of what it selects";
    EXPECT_NE(text.find("#define " + d.name + " " + std::to_string(d.value) + "\n"),
              std::string::npos)
        << d.name;
  }
  EXPECT_GE(names.size(), std::size_t(kTextureSlotCount) + 20);
}

// A define no shader reads is a feature that changes nothing but the program's key.
TEST(GlShaderPermutations, TheSurfaceShadersReadEveryDefine) {
  const std::string shaders = expand_shader("pbr_vertex.glsl") + expand_shader("pbr_fragment.glsl");
  for (const SurfaceDefine& d : SurfaceFeatures{}.define_list())
    EXPECT_NE(shaders.find(d.name), std::string::npos) << d.name << " is read by no shader";
}

// The surface program's own files take their features from the list alone: none defines a
// default that could hide a define the list stopped writing.
TEST(GlShaderPermutations, TheSurfaceFilesDefineNoFeature) {
  for (const char* file :
       {"pbr_fragment.glsl", "surface_light_punctual.glsl", "surface_light_indirect.glsl"}) {
    const std::string text(shader_source(file));
    ASSERT_FALSE(text.empty()) << file;
    for (const SurfaceDefine& d : SurfaceFeatures{}.define_list())
      EXPECT_EQ(text.find("#define " + d.name + " "), std::string::npos) << file << ": " << d.name;
  }
}

}  // namespace
}  // namespace pbrkit::gl
