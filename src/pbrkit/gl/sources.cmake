# The OpenGL renderer (headless through EGL, or in any current context such as the
# viewer's window: apps/viewer). Its shaders are the
# .glsl files in shaders/, embedded into the library at build time by embed_shaders.cmake
# (one generated .cpp holding every file's bytes), so the binary needs no data files.
set(_pbrkit_gl_dir ${CMAKE_CURRENT_SOURCE_DIR}/pbrkit/gl)
file(GLOB _pbrkit_gl_shaders CONFIGURE_DEPENDS ${_pbrkit_gl_dir}/shaders/*.glsl)
set(_pbrkit_gl_embedded ${CMAKE_CURRENT_BINARY_DIR}/pbrkit_gl_shaders.cpp)
add_custom_command(
  OUTPUT ${_pbrkit_gl_embedded}
  COMMAND ${CMAKE_COMMAND} -DSHADER_DIR=${_pbrkit_gl_dir}/shaders -DOUTPUT=${_pbrkit_gl_embedded}
          -P ${_pbrkit_gl_dir}/embed_shaders.cmake
  DEPENDS ${_pbrkit_gl_shaders} ${_pbrkit_gl_dir}/embed_shaders.cmake
  COMMENT "Embedding GLSL shaders"
  VERBATIM)
target_sources(pbrkit PRIVATE
  ${_pbrkit_gl_dir}/context.cpp
  ${_pbrkit_gl_dir}/program.cpp
  ${_pbrkit_gl_dir}/shaders.cpp
  ${_pbrkit_gl_dir}/debug_channels.cpp
  ${_pbrkit_gl_dir}/energy_texture.cpp
  ${_pbrkit_gl_dir}/ibl_maps.cpp
  ${_pbrkit_gl_dir}/gpu_scene.cpp
  ${_pbrkit_gl_dir}/gpu_deformation.cpp
  ${_pbrkit_gl_dir}/light_clusters.cpp
  ${_pbrkit_gl_dir}/occluders.cpp
  ${_pbrkit_gl_dir}/occluder_pass.cpp
  ${_pbrkit_gl_dir}/draw_queue.cpp
  ${_pbrkit_gl_dir}/surface_bindings.cpp
  ${_pbrkit_gl_dir}/shader_permutations.cpp
  ${_pbrkit_gl_dir}/render_targets.cpp
  ${_pbrkit_gl_dir}/gpu_timer.cpp
  ${_pbrkit_gl_dir}/renderer.cpp
  ${_pbrkit_gl_embedded})

# The shader unit tests' harness (testing/: a compute shader per model file, run over a
# batch of cases and read back, so tests/gl can compare GLSL with the C++), a static
# library of its own that only gl_tests links: the installed libpbrkit carries neither
# its code nor its testing/shaders/*_test.glsl, which it embeds the same way in a table of
# its own (compute_eval.h's test_program adds it to shader_source()'s on first use).
file(GLOB _pbrkit_gl_test_shaders CONFIGURE_DEPENDS ${_pbrkit_gl_dir}/testing/shaders/*.glsl)
set(_pbrkit_gl_test_embedded ${CMAKE_CURRENT_BINARY_DIR}/pbrkit_gl_test_shaders.cpp)
add_custom_command(
  OUTPUT ${_pbrkit_gl_test_embedded}
  COMMAND ${CMAKE_COMMAND} -DSHADER_DIR=${_pbrkit_gl_dir}/testing/shaders
          -DOUTPUT=${_pbrkit_gl_test_embedded} -DTABLE=kTestShaders
          -P ${_pbrkit_gl_dir}/embed_shaders.cmake
  DEPENDS ${_pbrkit_gl_test_shaders} ${_pbrkit_gl_dir}/embed_shaders.cmake
  COMMENT "Embedding the GLSL shader unit tests"
  VERBATIM)
add_library(pbrkit_gl_testing STATIC EXCLUDE_FROM_ALL
  ${_pbrkit_gl_dir}/testing/anisotropy_eval.cpp
  ${_pbrkit_gl_dir}/testing/brdf_eval.cpp
  ${_pbrkit_gl_dir}/testing/bsdf_eval.cpp
  ${_pbrkit_gl_dir}/testing/compute_eval.cpp
  ${_pbrkit_gl_dir}/testing/display_eval.cpp
  ${_pbrkit_gl_dir}/testing/iridescence_eval.cpp
  ${_pbrkit_gl_dir}/testing/occluder_eval.cpp
  ${_pbrkit_gl_dir}/testing/sheen_eval.cpp
  ${_pbrkit_gl_dir}/testing/transmission_eval.cpp
  ${_pbrkit_gl_test_embedded})
target_link_libraries(pbrkit_gl_testing PUBLIC pbrkit_internal)
