#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace luxel::testing {

/// The source checkout the tests and benchmarks read levels, corpora and scripts from.
///
/// These are functions of one configured source file (tests/support/test_paths.cpp.in, built
/// into luxel_test_paths), not macros on every test file's command line: a path in a compile
/// command is part of ccache's key, so a fresh clone at another path (CI's) recompiled every
/// test file. Now only that one file names the checkout.
[[nodiscard]] const std::filesystem::path& source_dir();

/// The build folder the tests were configured in (its bin/ holds the programs under test).
[[nodiscard]] const std::filesystem::path& binary_dir();

/// One of the build's programs (`luxel-sandbox`, `luxel-ref`, ...): every target's executable
/// lands in binary_dir()/bin (CMAKE_RUNTIME_OUTPUT_DIRECTORY). The suites that run one depend
/// on its target, so it is built first.
[[nodiscard]] std::string program(std::string_view name);

}  // namespace luxel::testing
