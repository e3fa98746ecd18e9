target_sources(pbrkit PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/cubemap.cpp
  ${CMAKE_CURRENT_LIST_DIR}/spherical_harmonics.cpp
  ${CMAKE_CURRENT_LIST_DIR}/brdf_lut.cpp
  ${CMAKE_CURRENT_LIST_DIR}/roughness_mapping.cpp
  ${CMAKE_CURRENT_LIST_DIR}/environment_cube.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prefilter.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sheen_prefilter.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sheen_lut.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sheen_sh.cpp
  ${CMAKE_CURRENT_LIST_DIR}/irradiance_cube.cpp
  ${CMAKE_CURRENT_LIST_DIR}/bake.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prefilter_kernels.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prefilter_validation.cpp
  ${CMAKE_CURRENT_LIST_DIR}/ktx2.cpp
  ${CMAKE_CURRENT_LIST_DIR}/bake_output.cpp
  ${CMAKE_CURRENT_LIST_DIR}/anisotropic_taps.cpp
  ${CMAKE_CURRENT_LIST_DIR}/anisotropic_albedo.cpp)
