# Compiler options shared by every luxel target, applied through luxel_target_defaults().

if(NOT CMAKE_CXX_COMPILER_LAUNCHER)
    find_program(LUXEL_CCACHE ccache)
    if(LUXEL_CCACHE)
        set(CMAKE_C_COMPILER_LAUNCHER ${LUXEL_CCACHE})
        set(CMAKE_CXX_COMPILER_LAUNCHER ${LUXEL_CCACHE})
    endif()
endif()

add_library(luxel_warnings INTERFACE)
target_compile_options(luxel_warnings INTERFACE
    $<$<COMPILE_LANGUAGE:CXX>:-Wall -Wextra -Wpedantic -Werror -Wshadow -Wnon-virtual-dtor
                              -Wold-style-cast -Wcast-align -Woverloaded-virtual>)

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

# Applies warnings-as-errors and the sanitizer flags to one of our own targets.
function(luxel_target_defaults target)
    get_target_property(_type ${target} TYPE)
    if(_type STREQUAL "INTERFACE_LIBRARY")
        target_link_libraries(${target} INTERFACE luxel_sanitize)
    else()
        target_link_libraries(${target} PRIVATE luxel_warnings)
        target_link_libraries(${target} PUBLIC luxel_sanitize)
    endif()
endfunction()
