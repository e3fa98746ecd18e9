# Every dependency comes from Debian 12 packages installed by scripts/setup.
# Each line's comment names the imported target as Debian packages it: embree's has no
# namespace, TinyGLTF is Debian's prebuilt libtinygltf.so (so no TINYGLTF_IMPLEMENTATION
# here), and stb's implementations are compiled into Debian's libstb.so.
find_package(embree 3 CONFIG REQUIRED)           # target: embree (no namespace)
find_package(TBB CONFIG REQUIRED)                # TBB::tbb
find_package(OpenEXR 3 CONFIG REQUIRED)          # OpenEXR::OpenEXR
find_package(PNG REQUIRED)                       # PNG::PNG (libpng: 8- and 16-bit PNG writing)
find_package(glm CONFIG REQUIRED)                # glm::glm
find_package(CLI11 2 CONFIG REQUIRED)            # CLI11::CLI11
find_package(nlohmann_json 3.11 CONFIG REQUIRED) # nlohmann_json::nlohmann_json
find_package(fmt 9 CONFIG REQUIRED)              # fmt::fmt
find_package(TinyGLTF CONFIG REQUIRED)           # TinyGLTF::TinyGLTF (Debian's prebuilt libtinygltf.so)
find_package(draco CONFIG REQUIRED)              # draco::draco
find_package(meshoptimizer CONFIG REQUIRED)      # meshoptimizer::meshoptimizer
find_package(OpenGL REQUIRED COMPONENTS OpenGL EGL)
find_package(ZLIB REQUIRED)                      # ZLIB::ZLIB (the learned denoiser's CRC-32)
# oneDNN 2.6 (libdnnl-dev), the learned denoiser's network. Found by hand, not through its
# dnnl-config.cmake: Debian built it with an OpenCL GPU runtime, and that file requires
# OpenCL's headers, which the CPU engine pbrkit uses never includes. Its CPU runtime is
# OpenMP (libgomp: DNNL_CPU_RUNTIME OMP in dnnl_config.h), so libgomp is linked too, for
# the thread count (omp_set_num_threads).
find_path(DNNL_INCLUDE_DIR oneapi/dnnl/dnnl.hpp REQUIRED)
find_library(DNNL_LIBRARY dnnl REQUIRED)
add_library(pbrkit_dnnl INTERFACE IMPORTED)      # pbrkit_dnnl
target_include_directories(pbrkit_dnnl SYSTEM INTERFACE ${DNNL_INCLUDE_DIR})
target_link_libraries(pbrkit_dnnl INTERFACE ${DNNL_LIBRARY} gomp)
find_package(glfw3 3.3 CONFIG REQUIRED)          # glfw
find_package(PkgConfig REQUIRED)
pkg_check_modules(STB REQUIRED IMPORTED_TARGET stb)      # PkgConfig::STB (implementations in libstb.so)
pkg_check_modules(EPOXY REQUIRED IMPORTED_TARGET epoxy)  # PkgConfig::EPOXY
pkg_check_modules(IMGUI REQUIRED IMPORTED_TARGET imgui)  # PkgConfig::IMGUI (backends inside libimgui.a)
if(PBRKIT_BUILD_TESTS)
  find_package(GTest CONFIG REQUIRED)            # GTest::gtest GTest::gtest_main
  include(GoogleTest)
endif()
if(PBRKIT_BUILD_BENCH)
  find_package(benchmark CONFIG REQUIRED)        # benchmark::benchmark
endif()
