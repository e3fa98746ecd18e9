target_sources(pbrkit PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/primitives.cpp)
