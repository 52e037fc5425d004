#pragma once

#include <sys/wait.h>
#include <array>
#include <cstdio>
#include <string>

namespace luxel::testing {

struct SandboxResult {
    int exit_code = -1;
    std::string output;  // stdout and stderr together
};

/// Runs build/bin/luxel-sandbox with `arguments` and collects what it printed.
inline SandboxResult run_sandbox(const std::string& arguments) {
    const std::string command = std::string(LUXEL_SANDBOX_EXECUTABLE) + " " + arguments + " 2>&1";
    SandboxResult result;
    FILE* pipe = ::popen(command.c_str(), "r");
    if (pipe == nullptr) {
        return result;
    }
    std::array<char, 4096> buffer{};
    while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) {
        result.output += buffer.data();
    }
    const int status = ::pclose(pipe);
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

}  // namespace luxel::testing
