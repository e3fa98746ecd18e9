target_sources(pbrkit PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/atomic_file.cpp
  ${CMAKE_CURRENT_LIST_DIR}/available_memory.cpp
  ${CMAKE_CURRENT_LIST_DIR}/data_dir.cpp
  ${CMAKE_CURRENT_LIST_DIR}/log.cpp
  ${CMAKE_CURRENT_LIST_DIR}/progress.cpp)
