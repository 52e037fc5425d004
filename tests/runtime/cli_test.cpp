// The command-line helpers every tool shares (luxel/runtime/cli.hpp, tool_main.hpp): usage
// mistakes become UsageError (exit 2), failures while running exit 1, help exits 0.

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "luxel/runtime/cli.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/runtime/tool_main.hpp"

namespace {

/// Parses `arguments` into a small app with the shared flags.
bool parse(std::vector<std::string> arguments, int& threads) {
    CLI::App app{"test"};
    luxel::cli::add_threads(app, threads);
    luxel::cli::add_log_level(app);
    arguments.insert(arguments.begin(), "tool");
    std::vector<char*> argv;
    for (std::string& argument : arguments) {
        argv.push_back(argument.data());
    }
    return luxel::cli::parse(app, static_cast<int>(argv.size()), argv.data());
}

TEST(Cli, SharedFlagsAreCheckedOnce) {
    int threads = 0;
    EXPECT_TRUE(parse({"--threads", "3", "--log-level", "warn"}, threads));
    EXPECT_EQ(threads, 3);
    for (const auto& bad : std::vector<std::vector<std::string>>{{"--threads", "-1"},
                                                                 {"--threads", "2000"},
                                                                 {"--threads", "two"},
                                                                 {"--log-level", "loud"},
                                                                 {"--unknown"}}) {
        try {
            (void)parse(bad, threads);
            ADD_FAILURE() << bad[0] << " accepted";
        } catch (const luxel::UsageError& e) {
            EXPECT_NE(std::string(e.what()).find(bad[0]), std::string::npos) << e.what();
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
        }
    }
}

TEST(Cli, HelpIsNotAnError) {
    int threads = 0;
    testing::internal::CaptureStdout();
    EXPECT_FALSE(parse({"--help"}, threads));
    EXPECT_NE(testing::internal::GetCapturedStdout().find("--threads"), std::string::npos);
}

TEST(Cli, RunToolMapsErrorsToExitStatus) {
    testing::internal::CaptureStderr();
    EXPECT_EQ(luxel::run_tool(
                  "t", [](int, char**) -> int { throw luxel::UsageError("--x"); }, 0, nullptr),
              2);
    EXPECT_EQ(luxel::run_tool(
                  "t", [](int, char**) -> int { throw luxel::Error("f.glb"); }, 0, nullptr),
              1);
    EXPECT_EQ(luxel::run_tool(
                  "t", [](int, char**) -> int { throw std::bad_alloc(); }, 0, nullptr),
              1);
    EXPECT_EQ(luxel::run_tool(
                  "t", [](int, char**) { return 0; }, 0, nullptr),
              0);
    const std::string errors = testing::internal::GetCapturedStderr();
    EXPECT_NE(errors.find("t: error: --x (see t --help)\n"), std::string::npos) << errors;
    EXPECT_NE(errors.find("t: error: f.glb\n"), std::string::npos) << errors;
    EXPECT_NE(errors.find("t: error: out of memory\n"), std::string::npos) << errors;
}

}  // namespace
