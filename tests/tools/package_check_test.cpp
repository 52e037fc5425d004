// scripts/check-packages.py, the check .ci/run makes after the build: every file from outside
// the repository that the build read must come from a package in the install closure of
// scripts/packages.txt. Fed a dependency listing here, with the real package list and with
// trimmed ones, so it is shown to fail where a new machine would.

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "run_command.hpp"
#include "temp_dir.hpp"
#include "test_paths.hpp"

namespace {

using luxel::testing::CommandResult;
using luxel::testing::quoted;

const std::filesystem::path kSource = luxel::testing::source_dir();
const std::filesystem::path kBuild = luxel::testing::binary_dir();

// A header GLFW's native-access header reads on X11; Debian's libxrandr-dev owns it. It went
// missing from scripts/packages.txt once, and only a new machine noticed.
const std::filesystem::path kXrandrHeader = "/usr/include/X11/extensions/Xrandr.h";

/// A `ninja -t deps` listing of one object that read `headers`.
void write_deps(const std::filesystem::path& file,
                std::initializer_list<std::filesystem::path> headers) {
    std::ofstream out(file);
    out << "runtime/CMakeFiles/luxel_runtime.dir/src/gl_context_window.cpp.o: #deps "
        << headers.size() << ", deps mtime 1 (VALID)\n";
    out << "    " << (kSource / "runtime/src/gl_context_window.cpp").string() << "\n";
    for (const auto& header : headers) {
        out << "    " << header.string() << "\n";
    }
    out << "\n";
}

CommandResult check(const std::filesystem::path& deps, const std::filesystem::path& packages) {
    return luxel::testing::run_command(
        (kSource / "scripts/check-packages.py").string(),
        quoted(kBuild) + " --deps " + quoted(deps) + " --packages " + quoted(packages));
}

TEST(PackageCheck, AHeaderFromAListedPackagePasses) {
    ASSERT_TRUE(std::filesystem::exists(kXrandrHeader)) << "scripts/setup.sh installs it";
    luxel::testing::TempDir dir("luxel-package-check");
    write_deps(dir / "deps.txt", {kXrandrHeader, "/usr/include/stdio.h"});
    const CommandResult result = check(dir / "deps.txt", kSource / "scripts/packages.txt");
    EXPECT_EQ(result.exit_code, 0) << result.output;
    EXPECT_NE(result.output.find("package check: 2 files"), std::string::npos) << result.output;
}

TEST(PackageCheck, AHeaderWhosePackageIsNotListedFailsWithTheLineToAdd) {
    luxel::testing::TempDir dir("luxel-package-check");
    write_deps(dir / "deps.txt", {kXrandrHeader, "/usr/include/stdio.h"});
    // The real list without libxrandr-dev: nothing else in it depends on that package.
    {
        std::ifstream in(kSource / "scripts/packages.txt");
        std::ofstream out(dir / "packages.txt");
        for (std::string line; std::getline(in, line);) {
            if (line != "libxrandr-dev") {
                out << line << "\n";
            }
        }
    }
    const CommandResult result = check(dir / "deps.txt", dir / "packages.txt");
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_NE(result.output.find(kXrandrHeader.string()), std::string::npos) << result.output;
    EXPECT_NE(result.output.find("missing package: libxrandr-dev"), std::string::npos)
        << result.output;
    EXPECT_NE(result.output.find("add the line 'libxrandr-dev'"), std::string::npos)
        << result.output;
    // stdio.h is libc6-dev's, which build-essential brings: it is not reported.
    EXPECT_EQ(result.output.find("stdio.h"), std::string::npos) << result.output;
}

TEST(PackageCheck, AFileThatNoPackageOwnsFails) {
    luxel::testing::TempDir dir("luxel-package-check");
    // A header installed by hand (here: written by the test) outside the repository.
    std::ofstream(dir / "hand_built.h") << "#pragma once\n";
    write_deps(dir / "deps.txt", {dir / "hand_built.h"});
    const CommandResult result = check(dir / "deps.txt", kSource / "scripts/packages.txt");
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_NE(result.output.find("no package: " + (dir / "hand_built.h").string()),
              std::string::npos)
        << result.output;
}

TEST(PackageCheck, APackageListedButNotInstalledFails) {
    luxel::testing::TempDir dir("luxel-package-check");
    write_deps(dir / "deps.txt", {"/usr/include/stdio.h"});
    std::ofstream(dir / "packages.txt") << "# a comment\nbuild-essential\nno-such-package-luxel\n";
    const CommandResult result = check(dir / "deps.txt", dir / "packages.txt");
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_NE(result.output.find("no-such-package-luxel"), std::string::npos) << result.output;
}

}  // namespace
