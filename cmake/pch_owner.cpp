// The one source of the targets that build luxel's precompiled headers (luxel_pch_core,
// luxel_pch_tests; cmake/LuxelCompilerOptions.cmake): CMake builds a target's precompiled header
// alongside its sources, so the target needs one, and every other target reuses the header.
