# Finds walkrad's dependencies, all from Debian packages (scripts/install-deps.sh installs them).
# Facts and pitfalls: ../shared/design/deps.md.
find_package(PkgConfig REQUIRED)
find_package(Threads REQUIRED)
find_package(nlohmann_json 3 CONFIG REQUIRED)
find_package(draco CONFIG REQUIRED)
pkg_check_modules(STB REQUIRED IMPORTED_TARGET stb)

if(WALKRAD_BUILD_PIPELINE)
  find_package(TBB CONFIG REQUIRED)
  find_package(embree 3 CONFIG REQUIRED)
  find_package(meshoptimizer CONFIG REQUIRED)
  pkg_check_modules(POLYCLIPPING REQUIRED IMPORTED_TARGET polyclipping)  # Clipper: a scene's openings
  find_package(CLI11 CONFIG REQUIRED)
  # Open MPI (a bake over several ranks: walkrad/core/ranks.h); the runtime never links it.
  find_package(MPI REQUIRED COMPONENTS CXX)
  # OpenVDB (the extinction grid of volume clusters) ships only a Find module, which sets
  # BUILD_SHARED_LIBS=ON in the caller's scope and needs Boost iostreams: keep ours.
  set(_walkrad_shared_libs ${BUILD_SHARED_LIBS})
  list(APPEND CMAKE_MODULE_PATH /usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/OpenVDB)
  find_package(OpenVDB REQUIRED COMPONENTS openvdb)
  set(BUILD_SHARED_LIBS ${_walkrad_shared_libs})
endif()

if(WALKRAD_BUILD_RUNTIME)
  find_package(OpenGL REQUIRED COMPONENTS OpenGL EGL)
  find_package(glfw3 3.3 CONFIG REQUIRED)
  pkg_check_modules(EPOXY REQUIRED IMPORTED_TARGET epoxy)
  if(NOT TARGET CLI11::CLI11)
    find_package(CLI11 CONFIG REQUIRED)
  endif()
endif()
