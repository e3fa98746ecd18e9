target_sources(pbrkit PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/adaptive_sampling.cpp
  ${CMAKE_CURRENT_LIST_DIR}/environment_sampler.cpp
  ${CMAKE_CURRENT_LIST_DIR}/film.cpp
  ${CMAKE_CURRENT_LIST_DIR}/geometry.cpp
  ${CMAKE_CURRENT_LIST_DIR}/guiding.cpp
  ${CMAKE_CURRENT_LIST_DIR}/integrator.cpp
  ${CMAKE_CURRENT_LIST_DIR}/light_bvh.cpp
  ${CMAKE_CURRENT_LIST_DIR}/lights.cpp
  ${CMAKE_CURRENT_LIST_DIR}/path_tracer.cpp
  ${CMAKE_CURRENT_LIST_DIR}/pixel_filter.cpp
  ${CMAKE_CURRENT_LIST_DIR}/progressive_render.cpp
  ${CMAKE_CURRENT_LIST_DIR}/shading.cpp)
