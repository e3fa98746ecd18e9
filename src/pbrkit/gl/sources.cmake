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
