target_sources(pbrkit PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/cross_filter.cpp
  ${CMAKE_CURRENT_LIST_DIR}/denoiser.cpp
  ${CMAKE_CURRENT_LIST_DIR}/denoiser_choice.cpp
  ${CMAKE_CURRENT_LIST_DIR}/denoiser_driven_sampling.cpp
  ${CMAKE_CURRENT_LIST_DIR}/energy.cpp
  ${CMAKE_CURRENT_LIST_DIR}/feature_prefilter.cpp
  ${CMAKE_CURRENT_LIST_DIR}/first_order.cpp
  ${CMAKE_CURRENT_LIST_DIR}/half_buffer_variance.cpp
  ${CMAKE_CURRENT_LIST_DIR}/inputs.cpp
  ${CMAKE_CURRENT_LIST_DIR}/outliers.cpp
  ${CMAKE_CURRENT_LIST_DIR}/planes.cpp
  ${CMAKE_CURRENT_LIST_DIR}/selection.cpp
  # the learned denoiser (docs/LEARNED_DENOISER.md)
  ${CMAKE_CURRENT_LIST_DIR}/learned/input_transform.cpp
  ${CMAKE_CURRENT_LIST_DIR}/learned/kernels.cpp
  ${CMAKE_CURRENT_LIST_DIR}/learned/learned_denoiser.cpp
  ${CMAKE_CURRENT_LIST_DIR}/learned/network.cpp
  ${CMAKE_CURRENT_LIST_DIR}/learned/tiles.cpp
  ${CMAKE_CURRENT_LIST_DIR}/learned/weights_file.cpp)
