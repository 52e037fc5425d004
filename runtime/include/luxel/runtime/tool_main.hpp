#pragma once

#include <exception>
#include <iostream>
#include <new>
#include <string_view>

#include "luxel/runtime/cli.hpp"
#include "luxel/runtime/error.hpp"

namespace luxel {

/// The body of a command-line tool's main(): runs `run(argc, argv)` and turns any error that
/// escapes into one line "<tool>: error: <what>" on stderr, so a bad file or flag never ends in
/// a crash. Exit status (luxel/runtime/cli.hpp): 2 for a UsageError, 1 for any other failure.
template <class Run>
int run_tool(std::string_view tool, Run&& run, int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const UsageError& e) {
        std::cerr << tool << ": error: " << e.what() << " (see " << tool << " --help)\n";
        return cli::kExitUsage;
    } catch (const Error& e) {
        std::cerr << tool << ": error: " << e.what() << "\n";
    } catch (const std::bad_alloc&) {
        std::cerr << tool << ": error: out of memory\n";
    } catch (const std::exception& e) {
        std::cerr << tool << ": error: internal error: " << e.what() << "\n";
    }
    return cli::kExitFailure;
}

}  // namespace luxel
