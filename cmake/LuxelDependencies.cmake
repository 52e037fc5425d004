# Every third-party dependency comes from a Debian 12 package (scripts/setup.sh installs them).
# Config-file packages are found with find_package; the few that ship only a pkg-config file
# (OSMesa, stb, Dear ImGui) through pkg_check_modules.

find_package(Threads REQUIRED)
find_package(glm CONFIG REQUIRED)
find_package(glfw3 3.3 CONFIG REQUIRED)
find_package(embree 3 CONFIG REQUIRED)
find_package(TinyGLTF CONFIG REQUIRED)
find_package(OpenMesh CONFIG REQUIRED)
find_package(Eigen3 3.3 CONFIG REQUIRED)
find_package(nanoflann CONFIG REQUIRED)
find_package(TBB CONFIG REQUIRED)
find_package(tinyexr CONFIG REQUIRED)
find_package(nlohmann_json 3 CONFIG REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(OpenGL REQUIRED COMPONENTS EGL)
find_package(X11 REQUIRED)

find_package(PkgConfig REQUIRED)
pkg_check_modules(OSMesa REQUIRED IMPORTED_TARGET osmesa)
pkg_check_modules(stb REQUIRED IMPORTED_TARGET stb)

if(LUXEL_BUILD_TESTS)
    find_package(GTest CONFIG REQUIRED)
    find_program(LUXEL_XVFB_RUN xvfb-run REQUIRED)
endif()
if(LUXEL_BUILD_BENCHMARKS)
    find_package(benchmark CONFIG REQUIRED)
endif()
