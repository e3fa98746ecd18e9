target_sources(pbrkit PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/asset_uri.cpp
  ${CMAKE_CURRENT_LIST_DIR}/builtin_scenes.cpp
  ${CMAKE_CURRENT_LIST_DIR}/camera.cpp
  ${CMAKE_CURRENT_LIST_DIR}/gltf_container.cpp
  ${CMAKE_CURRENT_LIST_DIR}/gltf_loader.cpp
  ${CMAKE_CURRENT_LIST_DIR}/gltf_writer.cpp
  ${CMAKE_CURRENT_LIST_DIR}/load.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mesh_attributes.cpp
  ${CMAKE_CURRENT_LIST_DIR}/primitives.cpp
  ${CMAKE_CURRENT_LIST_DIR}/scene.cpp
  ${CMAKE_CURRENT_LIST_DIR}/texture.cpp)
