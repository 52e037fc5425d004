#pragma once

// Runs one of luxel's command-line tools from a test, the way a user would: through the shell,
// stdout and stderr together, with the exit status.

#include <sys/wait.h>
#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

namespace luxel::testing {

struct CommandResult {
    int exit_code = -1;  ///< -1: it did not exit normally (a crash or a signal)
    std::string output;  ///< stdout and stderr together
};

/// Runs `executable` with `arguments` (already quoted as the shell needs).
inline CommandResult run_command(const std::string& executable, const std::string& arguments) {
    std::string command("'");
    command += executable;
    command += "' ";
    command += arguments;
    command += " 2>&1";
    CommandResult result;
    FILE* pipe = ::popen(command.c_str(), "r");
    if (pipe == nullptr) {
        return result;
    }
    std::array<char, 4096> chunk{};
    while (std::fgets(chunk.data(), static_cast<int>(chunk.size()), pipe) != nullptr) {
        result.output += chunk.data();
    }
    const int status = ::pclose(pipe);
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

/// A path in single quotes for the shell.
inline std::string quoted(const std::filesystem::path& path) {
    // Appended, not "'" + string: GCC 12 warns (-Wrestrict) on that insert falsely.
    std::string text("'");
    text += path.string();
    text += "'";
    return text;
}

}  // namespace luxel::testing
