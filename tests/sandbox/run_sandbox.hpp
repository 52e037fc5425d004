#pragma once

#include <string>

#include "run_command.hpp"
#include "test_paths.hpp"

namespace luxel::testing {

using SandboxResult = CommandResult;

/// Runs build/bin/luxel-sandbox with `arguments` and collects what it printed.
inline SandboxResult run_sandbox(const std::string& arguments) {
    return run_command(luxel::testing::program("luxel-sandbox"), arguments);
}

}  // namespace luxel::testing
