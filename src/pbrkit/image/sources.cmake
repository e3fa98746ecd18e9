target_sources(pbrkit PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/display.cpp
  ${CMAKE_CURRENT_LIST_DIR}/environment.cpp
  ${CMAKE_CURRENT_LIST_DIR}/exr_io.cpp
  ${CMAKE_CURRENT_LIST_DIR}/image_io.cpp
  ${CMAKE_CURRENT_LIST_DIR}/output_paths.cpp
  ${CMAKE_CURRENT_LIST_DIR}/png_write.cpp
  ${CMAKE_CURRENT_LIST_DIR}/stb_io.cpp
  ${CMAKE_CURRENT_LIST_DIR}/compare.cpp)
