# Every dependency is a Debian 12 package (scripts/install-deps.sh installs them).
find_package(PkgConfig REQUIRED)
find_package(embree 3 REQUIRED)
find_package(TBB REQUIRED)
find_package(assimp REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(CLI11 REQUIRED)
# OpenEXR 3.1 (libopenexr-dev): OpenEXR::OpenEXR, the C++ library, and OpenEXR::OpenEXRCore, its C core.
find_package(OpenEXR 3.1 REQUIRED)
pkg_check_modules(STB REQUIRED IMPORTED_TARGET stb)
# Headless OpenGL through EGL (Mesa llvmpipe without a GPU): cube-addressing oracle, later the raster G-buffer.
pkg_check_modules(EPOXY REQUIRED IMPORTED_TARGET epoxy)
pkg_check_modules(EGL REQUIRED IMPORTED_TARGET egl)
# The interactive viewer (`raycache view`): GLFW window, Dear ImGui panel (Debian's libimgui-dev
# is a static library with the GLFW and OpenGL3 backends built in).
pkg_check_modules(GLFW REQUIRED IMPORTED_TARGET glfw3)
pkg_check_modules(IMGUI REQUIRED IMPORTED_TARGET imgui)
if(RAYCACHE_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
# Cluster mode (docs/cluster.md): Debian's Open MPI (libopenmpi-dev). Optional:
# without it raycache builds and runs as one process.
find_package(MPI COMPONENTS CXX QUIET)
option(RAYCACHE_MPI "Build the MPI cluster mode (src/cluster/); on when Open MPI is found" ${MPI_CXX_FOUND})
if(RAYCACHE_MPI AND NOT MPI_CXX_FOUND)
  message(FATAL_ERROR "RAYCACHE_MPI is on but no MPI (C++) was found: install libopenmpi-dev or turn it off")
endif()
