#pragma once

// The command line every luxel tool shares: how flags are parsed, how mistakes are reported,
// and the flags that several tools take, validated once here.
//
// The contract (README "Command-line tools"): exit 0 on success (and for --help), 2 for a
// usage error (unknown flag, bad value, missing argument), 1 for a failure while running (a bad
// file, no GL context, out of memory). Either error is one line on stderr,
// "<tool>: error: <what>", naming the flag or the file. luxel::run_tool prints it.

#include <string>

#include <CLI/CLI.hpp>

#include "luxel/runtime/error.hpp"

namespace luxel::cli {

inline constexpr int kExitSuccess = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitUsage = 2;

/// Parses argv into `app`. Returns false when help was asked for: it is printed to stdout and
/// the tool should exit 0. Every other mistake CLI11 finds is thrown as a luxel::UsageError
/// whose message names the flag.
[[nodiscard]] bool parse(CLI::App& app, int argc, char** argv);

/// --threads N: job threads, 0 for every core, at most 1024.
CLI::Option* add_threads(CLI::App& app, int& threads);

/// --log-level: trace, debug, info, warn, error or off; applied as soon as it is parsed.
CLI::Option* add_log_level(CLI::App& app);

/// Runs the checks of flag values that CLI11 cannot make itself (formats, combinations); any
/// luxel::Error they throw is a mistake on the command line, so it leaves as a UsageError.
template <class Checks>
void check_usage(Checks&& checks) {
    try {
        checks();
    } catch (const UsageError&) {
        throw;
    } catch (const Error& e) {
        throw UsageError(e.what());
    }
}

}  // namespace luxel::cli
