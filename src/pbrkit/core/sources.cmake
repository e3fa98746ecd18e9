target_sources(pbrkit PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/sampling.cpp
  ${CMAKE_CURRENT_LIST_DIR}/microfacet.cpp
  ${CMAKE_CURRENT_LIST_DIR}/energy.cpp
  ${CMAKE_CURRENT_LIST_DIR}/anisotropic_energy.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sheen.cpp
  ${CMAKE_CURRENT_LIST_DIR}/brdf.cpp
  ${CMAKE_CURRENT_LIST_DIR}/bsdf.cpp
  ${CMAKE_CURRENT_LIST_DIR}/transmission.cpp
  ${CMAKE_CURRENT_LIST_DIR}/dispersion.cpp
  ${CMAKE_CURRENT_LIST_DIR}/color.cpp
  ${CMAKE_CURRENT_LIST_DIR}/iridescence.cpp)
