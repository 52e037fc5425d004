# Compiler options shared by every luxel target, applied through luxel_target_defaults().

option(LUXEL_PCH "Precompile the standard and third-party headers that most files include" ON)
set(LUXEL_DEBUG_INFO "lines" CACHE STRING
    "Debug information in RelWithDebInfo builds: lines (-g1: line tables for stack traces and profilers) or full (-g, for a debugger)")
set_property(CACHE LUXEL_DEBUG_INFO PROPERTY STRINGS lines full)
if(NOT LUXEL_DEBUG_INFO MATCHES "^(lines|full)$")
    message(FATAL_ERROR "LUXEL_DEBUG_INFO must be 'lines' or 'full', not '${LUXEL_DEBUG_INFO}'")
endif()

if(NOT CMAKE_CXX_COMPILER_LAUNCHER)
    find_program(LUXEL_CCACHE ccache)
    if(LUXEL_CCACHE)
        # ccache caches compilations that use a precompiled header only with this sloppiness
        # (its manual, "Precompiled headers"); the header's own build is cached as well, so a
        # warm cache serves both. The environment variable is how ccache 4.7 takes it per build.
        set(_luxel_ccache ${CMAKE_COMMAND} -E env
            CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime
            ${LUXEL_CCACHE})
        set(CMAKE_C_COMPILER_LAUNCHER ${_luxel_ccache})
        set(CMAKE_CXX_COMPILER_LAUNCHER ${_luxel_ccache})
    endif()
endif()

add_library(luxel_warnings INTERFACE)
target_compile_options(luxel_warnings INTERFACE
    $<$<COMPILE_LANGUAGE:CXX>:-Wall -Wextra -Wpedantic -Werror -Wshadow -Wnon-virtual-dtor
                              -Wold-style-cast -Wcast-align -Woverloaded-virtual>)
if(LUXEL_DEBUG_INFO STREQUAL "lines")
    # Line tables name the file and line in every stack trace and profile; full debug info made
    # each file ~20% slower to compile and CI builds everything twice. It rides on
    # luxel_warnings because that is the options interface private to our own targets: the
    # third-party code we link is not compiled here.
    target_compile_options(luxel_warnings INTERFACE $<$<CONFIG:RelWithDebInfo>:-g1>)
endif()

add_library(luxel_sanitize INTERFACE)
if(LUXEL_SANITIZE)
    # ASan and UBSan on everything we compile; UBSan findings abort so a test cannot pass over them.
    set(_luxel_san_flags -fsanitize=address,undefined -fno-sanitize-recover=undefined
                         -fno-omit-frame-pointer)
    # -O1 -g1 (after the build type's -O2 -g, so they win): ASan's own advice for speed, and line
    # tables are all its stack traces need. Full debug info with the instrumentation made a test
    # file take 44 s to compile instead of 20 s, and the sanitized build is half of CI's time.
    target_compile_options(luxel_sanitize INTERFACE ${_luxel_san_flags} -O1 -g1)
    target_link_options(luxel_sanitize INTERFACE ${_luxel_san_flags})
    target_compile_definitions(luxel_sanitize INTERFACE LUXEL_SANITIZE=1)
    # ASan's instrumentation defeats GCC 12's flow analysis: -Wmaybe-uninitialized then fires
    # inside libstdc++ (std::regex, std::function) on code that is clean in the normal build,
    # where the warning stays an error.
    target_compile_options(luxel_sanitize INTERFACE
        $<$<CXX_COMPILER_ID:GNU>:-Wno-maybe-uninitialized>)
endif()
if(LUXEL_FUZZ AND CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    # Coverage instrumentation for libFuzzer in everything we compile, so the fuzzer sees the
    # branches of the code under test; only the fuzz targets link libFuzzer itself.
    target_compile_options(luxel_sanitize INTERFACE -fsanitize=fuzzer-no-link)
endif()

# The headers nearly every file includes (the standard library, glm, nlohmann::json, GoogleTest),
# parsed once per build instead of once per file: with line-table debug info they took a sample
# of files from 68 s to 52 s. Two headers, each built once by a target of its own and reused by
# every target of its kind: GCC uses a precompiled header only where the macros it was built
# with are defined the same way, and the tests' GTEST_HAS_PTHREAD and -pthread must not leak
# into the libraries. A target whose flags do not match fails the build (-Winvalid-pch under
# -Werror) rather than silently parsing everything again. The headers are still included by
# the files that use them, so a build with -DLUXEL_PCH=OFF compiles the same sources.
set(LUXEL_PCH_HEADERS
    <algorithm> <array> <cmath> <cstddef> <cstdint> <cstdio> <filesystem> <fstream> <functional>
    <limits> <map> <memory> <optional> <random> <span> <string> <string_view> <utility> <vector>
    <glm/glm.hpp> <glm/gtc/constants.hpp> <glm/gtc/matrix_transform.hpp> <glm/gtc/quaternion.hpp>
    <nlohmann/json.hpp>)

function(_luxel_pch_owner owner)
    if(TARGET ${owner})
        return()
    endif()
    add_library(${owner} OBJECT ${PROJECT_SOURCE_DIR}/cmake/pch_owner.cpp)
    target_link_libraries(${owner} PRIVATE luxel_warnings luxel_sanitize glm::glm
                                           nlohmann_json::nlohmann_json)
    set(_headers ${LUXEL_PCH_HEADERS})
    if(owner STREQUAL "luxel_pch_tests")
        target_link_libraries(${owner} PRIVATE GTest::gtest)
        list(APPEND _headers <gtest/gtest.h>)
    endif()
    target_precompile_headers(${owner} PRIVATE ${_headers})
endfunction()

# Applies warnings-as-errors, the sanitizer flags and the precompiled headers to one of our own
# targets. Call it after the target's target_link_libraries: a target that links GoogleTest
# gets the tests' precompiled header.
function(luxel_target_defaults target)
    get_target_property(_type ${target} TYPE)
    if(_type STREQUAL "INTERFACE_LIBRARY")
        target_link_libraries(${target} INTERFACE luxel_sanitize)
        return()
    endif()
    target_link_libraries(${target} PRIVATE luxel_warnings)
    target_link_libraries(${target} PUBLIC luxel_sanitize)
    if(LUXEL_PCH)
        get_target_property(_links ${target} LINK_LIBRARIES)
        if("GTest::gtest" IN_LIST _links)
            set(_owner luxel_pch_tests)
        else()
            set(_owner luxel_pch_core)
        endif()
        _luxel_pch_owner(${_owner})
        target_precompile_headers(${target} REUSE_FROM ${_owner})
    endif()
endfunction()
