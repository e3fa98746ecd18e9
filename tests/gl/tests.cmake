# gl_tests: tests/gl/*_test.cpp, with the shader unit tests' harness (harness/: a compute
# shader per model file, run over a batch of cases and read back, so the tests can compare
# GLSL with the C++). The harness is a static library of its own in the test tree, so the
# installed libpbrkit carries neither its code nor its harness/shaders/*_test.glsl; those are
# embedded the same way as the library's shaders (src/pbrkit/gl/embed_shaders.cmake), in a
# table of their own that compute_eval.h's test_program adds to shader_source()'s on first use.
set(_gl_harness_dir ${CMAKE_CURRENT_LIST_DIR}/harness)
set(_gl_embed_script ${PROJECT_SOURCE_DIR}/src/pbrkit/gl/embed_shaders.cmake)
file(GLOB _gl_harness_shaders CONFIGURE_DEPENDS ${_gl_harness_dir}/shaders/*.glsl)
set(_gl_harness_embedded ${CMAKE_CURRENT_BINARY_DIR}/pbrkit_gl_harness_shaders.cpp)
add_custom_command(
  OUTPUT ${_gl_harness_embedded}
  COMMAND ${CMAKE_COMMAND} -DSHADER_DIR=${_gl_harness_dir}/shaders
          -DOUTPUT=${_gl_harness_embedded} -DTABLE=kTestShaders -P ${_gl_embed_script}
  DEPENDS ${_gl_harness_shaders} ${_gl_embed_script}
  COMMENT "Embedding the GLSL shader unit tests"
  VERBATIM)
add_library(pbrkit_gl_harness STATIC EXCLUDE_FROM_ALL
  ${_gl_harness_dir}/anisotropy_eval.cpp
  ${_gl_harness_dir}/brdf_eval.cpp
  ${_gl_harness_dir}/bsdf_eval.cpp
  ${_gl_harness_dir}/compute_eval.cpp
  ${_gl_harness_dir}/display_eval.cpp
  ${_gl_harness_dir}/iridescence_eval.cpp
  ${_gl_harness_dir}/occluder_eval.cpp
  ${_gl_harness_dir}/sheen_eval.cpp
  ${_gl_harness_dir}/transmission_eval.cpp
  ${_gl_harness_embedded})
# Included as "gl/harness/<name>.h" from the tests' root, as the other test helpers are.
target_include_directories(pbrkit_gl_harness PUBLIC ${CMAKE_CURRENT_SOURCE_DIR})
target_link_libraries(pbrkit_gl_harness PUBLIC pbrkit_internal)
pbrkit_add_tests(gl pbrkit_gl_harness)
