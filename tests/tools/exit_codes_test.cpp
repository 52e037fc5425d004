// The contract every luxel tool keeps on the command line (README "Command-line tools"): exit 0
// on success and for --help, 2 for a usage error, 1 for a failure while running, and each error
// one line "<tool>: error: ..." naming the flag or the file. Scripts depend on these codes, so
// each tool is run here as a user would run it.

#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "run_command.hpp"
#include "temp_dir.hpp"
#include "test_paths.hpp"

namespace {

using luxel::testing::CommandResult;
using luxel::testing::run_command;

struct Tool {
    const char* name;
    std::string executable;
};

const Tool kSandbox{"luxel-sandbox", luxel::testing::program("luxel-sandbox")};
const Tool kPrep{"luxel-prep", luxel::testing::program("luxel-prep")};
const Tool kRef{"luxel-ref", luxel::testing::program("luxel-ref")};
const Tool kBench{"luxel-bench", luxel::testing::program("luxel-bench")};
const Tool kMakeLevels{"luxel-make-levels", luxel::testing::program("luxel-make-levels")};

const std::string kCornell = (luxel::testing::source_dir() / "assets/levels/cornell.glb").string();

struct Case {
    Tool tool;
    std::string arguments;  ///< "@" stands for a fresh temporary folder
    int exit_code;
    std::string names;  ///< what the error line must name: the flag or the file
};

std::ostream& operator<<(std::ostream& out, const Case& c) {
    return out << c.tool.name << " " << c.arguments;
}

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream stream(text);
    for (std::string line; std::getline(stream, line);) {
        lines.push_back(line);
    }
    return lines;
}

std::string with_folder(std::string arguments, const std::filesystem::path& folder) {
    for (std::size_t at = arguments.find('@'); at != std::string::npos;
         at = arguments.find('@', at)) {
        arguments.replace(at, 1, folder.string());
        at += folder.string().size();
    }
    return arguments;
}

class ExitCodes : public ::testing::TestWithParam<Case> {};

TEST_P(ExitCodes, ExitStatusAndOneErrorLineNamingTheCulprit) {
    const Case& c = GetParam();
    luxel::testing::TempDir folder("luxel-exit-codes");
    // A plain file where a folder is expected: outputs under it cannot be made.
    std::ofstream(folder / "blocker") << "x";
    const CommandResult result =
        run_command(c.tool.executable, with_folder(c.arguments, folder.path()));
    ASSERT_EQ(result.exit_code, c.exit_code) << result.output;

    const std::string prefix = std::string(c.tool.name) + ": error: ";
    std::vector<std::string> error_lines;
    for (const std::string& line : lines_of(result.output)) {
        if (line.rfind(prefix, 0) == 0) {
            error_lines.push_back(line);
        }
    }
    ASSERT_EQ(error_lines.size(), 1u) << "expected one line starting '" << prefix << "':\n"
                                      << result.output;
    EXPECT_NE(error_lines[0].find(with_folder(c.names, folder.path())), std::string::npos)
        << "the error should name '" << c.names << "': " << error_lines[0];
    if (c.exit_code == 2) {
        // A usage error is found before any work starts: nothing else is printed.
        EXPECT_EQ(lines_of(result.output).size(), 1u) << result.output;
    }
}

// clang-format off
INSTANTIATE_TEST_SUITE_P(Tools, ExitCodes, ::testing::Values(
    // luxel-sandbox
    Case{kSandbox, "--frames 1 --no-such-flag", 2, "--no-such-flag"},
    Case{kSandbox, "--threads -1", 2, "--threads"},
    Case{kSandbox, "--frames abc", 2, "--frames"},
    Case{kSandbox, "--gl vulkan", 2, "--gl"},
    Case{kSandbox, "--size 640by360", 2, "--size"},
    Case{kSandbox, "--log-level loud", 2, "--log-level"},
    Case{kSandbox, "--level", 2, "--level"},
    Case{kSandbox, "--frames 1 --level @/missing.glb", 1, "@/missing.glb"},
    // luxel-prep
    Case{kPrep, "@/in.glb -o @/out.glb --no-such-flag", 2, "--no-such-flag"},
    Case{kPrep, "@/in.glb", 2, "--output"},
    Case{kPrep, "@/in.glb -o @/out.glb --threads -1", 2, "--threads"},
    Case{kPrep, "@/in.glb -o @/out.glb --texel-size -1", 2, "--texel-size"},
    Case{kPrep, "@/in.glb -o @/out.glb --padding many", 2, "--padding"},
    Case{kPrep, "@/missing.glb -o @/out.glb", 1, "@/missing.glb"},
    Case{kPrep, "@/in.glb -o @/out.glb --limit bogus=1", 2, "--limit"},
    Case{kPrep, "@/in.glb -o @/out.glb --limit nodes=many", 2, "--limit"},
    Case{kPrep, kCornell + " -o @/out.glb --limit nodes=1", 1, "more than the limit of 1 nodes"},
    Case{kPrep, "@/blocker -o @/blocker", 2, "is the input"},
    // luxel-ref
    Case{kRef, "--level cornell -o @/f.exr --no-such-flag", 2, "--no-such-flag"},
    Case{kRef, "--level cornell -o @/f.exr --threads -1", 2, "--threads"},
    Case{kRef, "-o @/f.exr", 2, "--level"},
    Case{kRef, "--level cornell -o @/f.exr --spp 0", 2, "--spp"},
    Case{kRef, "--level cornell -o @/f.png", 2, "-o"},
    Case{kRef, "--level cornell -o @/f.exr --camera 1,2:3", 2, "--camera"},
    Case{kRef, "--level @/missing.glb -o @/f.exr", 1, "@/missing.glb"},
    Case{kRef, "--level cornell -o @/f.exr --limit lights", 2, "--limit"},
    // luxel-bench
    Case{kBench, "--level cornell --no-such-flag", 2, "--no-such-flag"},
    Case{kBench, "--level cornell --threads -1", 2, "--threads"},
    Case{kBench, "--budgets 1,x", 2, "--level"},
    Case{kBench, "--level cornell --budgets 1,x", 2, "--budgets"},
    Case{kBench, "--level cornell --sweep nonsense=1", 2, "nonsense"},
    Case{kBench, "--level @/missing.glb --out @/run", 1, "@/missing.glb"},
    Case{kBench, "--level cornell --limit triangles=1G1", 2, "--limit"},
    Case{kBench, "--level cornell --camera 1,2:3", 2, "--camera"},
    Case{kBench, "--level cornell --camera 0,1,3:0,1,0:60 --no-image", 2, "--camera"},
    // luxel-make-levels
    Case{kMakeLevels, "--no-such-flag", 2, "--no-such-flag"},
    Case{kMakeLevels, "--level no-such-level --out @/levels", 2, "no-such-level"},
    Case{kMakeLevels, "--level cornell --out @/blocker/levels", 1, "@/blocker/levels"}));
// clang-format on

TEST(ExitCodes, HelpExitsZeroOnStdout) {
    for (const Tool& tool : {kSandbox, kPrep, kRef, kBench, kMakeLevels}) {
        const CommandResult result = run_command(tool.executable, "--help");
        EXPECT_EQ(result.exit_code, 0) << tool.name << ": " << result.output;
        EXPECT_NE(result.output.find("--help"), std::string::npos) << tool.name;
        EXPECT_EQ(result.output.find(": error:"), std::string::npos) << result.output;
    }
}

}  // namespace
