#pragma once

// Runs the Khronos glTF validator (tools/validate-gltf.cjs, installed by scripts/setup.sh) on
// files. A missing Node.js or validator is a failure, not a skip: the project promises that
// everything it writes passes the validator.

#include <sys/wait.h>
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_paths.hpp"

namespace luxel::testing {

struct ValidatorResult {
    int exit_code = -1;  ///< 0: no errors; 1: errors; 2: unreadable; 127: node missing
    std::string output;
};

inline ValidatorResult run_gltf_validator(const std::vector<std::filesystem::path>& files) {
    const std::filesystem::path script =
        luxel::testing::source_dir() / "tools" / "validate-gltf.cjs";
    std::string command = "node '" + script.string() + "'";
    for (const auto& file : files) {
        command += " '" + file.string() + "'";
    }
    command += " 2>&1";
    ValidatorResult result;
    FILE* pipe = popen(command.c_str(), "r");
    if (pipe == nullptr) {
        result.output = "popen failed for: " + command;
        return result;
    }
    std::array<char, 4096> chunk{};
    while (std::fgets(chunk.data(), static_cast<int>(chunk.size()), pipe) != nullptr) {
        result.output += chunk.data();
    }
    const int status = pclose(pipe);
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

/// Every file passes: exit 0 and one summary line per file, no error lines.
inline void expect_every_file_valid(const std::vector<std::filesystem::path>& files) {
    const ValidatorResult result = run_gltf_validator(files);
    EXPECT_EQ(result.exit_code, 0) << result.output;
    EXPECT_EQ(std::count(result.output.begin(), result.output.end(), '\n'),
              static_cast<std::ptrdiff_t>(files.size()))
        << "one summary line per file, no error lines:\n"
        << result.output;
}

}  // namespace luxel::testing
