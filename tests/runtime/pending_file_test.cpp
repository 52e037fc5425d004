// Files that appear whole or not at all (luxel::PendingFile): an interrupted writer leaves the
// previous file, and no temporary file behind.

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "luxel/runtime/error.hpp"
#include "luxel/runtime/image.hpp"
#include "luxel/runtime/pending_file.hpp"
#include "temp_dir.hpp"

namespace {

std::string read_text(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::size_t files_in(const std::filesystem::path& folder) {
    return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(folder),
                                                  std::filesystem::directory_iterator()));
}

TEST(PendingFile, AWriterThatStopsHalfWayLeavesThePreviousFile) {
    luxel::testing::TempDir dir;
    const auto target = dir / "level.glb";
    std::ofstream(target) << "the good file";
    {
        luxel::PendingFile pending(target);
        EXPECT_EQ(pending.path().parent_path(), target.parent_path());
        std::ofstream(pending.path()) << "half of a new";
        // No commit: as when an exception, Ctrl-C's handler or a full disk ends the writer.
    }
    EXPECT_EQ(read_text(target), "the good file");
    EXPECT_EQ(files_in(dir.path()), 1u) << "the temporary file was left behind";
}

TEST(PendingFile, CommitReplacesTheTargetWhole) {
    luxel::testing::TempDir dir;
    const auto target = dir / "report.json";
    std::ofstream(target) << "old";
    const std::string text = "{\"new\": true}\n";
    luxel::write_file_atomically(target, std::as_bytes(std::span(text)));
    EXPECT_EQ(read_text(target), text);
    EXPECT_EQ(files_in(dir.path()), 1u);
}

TEST(PendingFile, AFolderThatDoesNotExistIsAnErrorNamingTheFile) {
    luxel::testing::TempDir dir;
    const auto target = dir / "missing" / "out.bin";
    const std::string text = "x";
    try {
        luxel::write_file_atomically(target, std::as_bytes(std::span(text)));
        FAIL() << "wrote into a folder that does not exist";
    } catch (const luxel::Error& e) {
        EXPECT_NE(std::string(e.what()).find(target.string()), std::string::npos) << e.what();
    }
}

TEST(PendingFile, ImagesAreWrittenThroughIt) {
    luxel::testing::TempDir dir;
    luxel::Image image(4, 2);
    luxel::write_png(dir / "frame.png", image);
    luxel::write_exr(dir / "frame.exr", image);
    EXPECT_EQ(files_in(dir.path()), 2u);
    EXPECT_EQ(luxel::read_exr(dir / "frame.exr").width, 4);
}

}  // namespace
