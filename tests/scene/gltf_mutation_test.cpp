// Deterministic mutation test: thousands of corrupted copies of valid glTF files (bit flips,
// truncations, byte swaps, overwritten integers, and JSON-level edits: deleted keys, changed
// numbers, wrong types, swapped values). Every copy must either load into a scene that passes
// Scene::validate() (and can be written again), or be rejected with a luxel::Error. Anything
// else — a crash, a sanitizer report, another exception type — fails the suite. The cases are
// numbered and seeded by their number, so a failing case can be rerun alone.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>

#include <gtest/gtest.h>

#include "gltf_test_files.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/runtime/log.hpp"
#include "luxel/scene/gltf.hpp"
#include "temp_dir.hpp"
#include "test_paths.hpp"
#include "test_scenes.hpp"

namespace {

using nlohmann::json;

/// One file to corrupt: its bytes, whether it is a GLB, and the directory its external
/// buffers live in (empty for self-contained files).
struct MutationInput {
    std::string name;
    std::vector<std::uint8_t> bytes;
    bool binary = false;
    std::filesystem::path base_dir;
};

std::vector<std::uint8_t> read_bytes(const std::filesystem::path& file) {
    std::ifstream stream(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
}

/// Directories whose .glb/.gltf files join the inputs when they exist: the built-in levels.
std::vector<std::filesystem::path> level_directories() {
    const std::filesystem::path root = luxel::testing::source_dir();
    return {root / "assets" / "levels", root / "tests" / "assets" / "levels"};
}

std::vector<MutationInput> mutation_inputs(const luxel::testing::TempDir& dir) {
    std::vector<MutationInput> inputs;
    for (const auto& [name, scene] : luxel::testing::mutation_seed_scenes()) {
        inputs.push_back(
            {name + ".glb",
             luxel::scene::save_gltf_to_memory(scene, luxel::scene::GltfContainer::Binary),
             true,
             {}});
        inputs.push_back(
            {name + "-embedded.gltf",
             luxel::scene::save_gltf_to_memory(scene, luxel::scene::GltfContainer::EmbeddedText),
             false,
             {}});
        // The JSON of a .gltf with its .bin beside it: corrupting the JSON against an intact
        // buffer file reaches the external-file paths.
        const std::filesystem::path file = dir / (name + ".gltf");
        luxel::scene::save_gltf(scene, file);
        inputs.push_back({name + ".gltf", read_bytes(file), false, dir.path()});
    }
    for (const std::filesystem::path& levels : level_directories()) {
        if (!std::filesystem::is_directory(levels)) {
            continue;
        }
        std::vector<std::filesystem::path> files;
        for (const auto& entry : std::filesystem::directory_iterator(levels)) {
            const std::string extension = entry.path().extension().string();
            if (extension == ".glb" || extension == ".gltf") {
                files.push_back(entry.path());
            }
        }
        std::sort(files.begin(), files.end());  // directory order is not deterministic
        for (const auto& file : files) {
            inputs.push_back(
                {file.filename().string(), read_bytes(file), file.extension() == ".glb", levels});
        }
    }
    return inputs;
}

/// Larger files (the built-in levels) get fewer cases so the suite stays within its time
/// budget under the sanitizers; the small seed scenes carry the bulk of the cases.
std::size_t cases_for(const MutationInput& input, std::size_t small_count) {
    if (input.bytes.size() > (std::size_t{1} << 20)) {
        return small_count / 40;
    }
    if (input.bytes.size() > (std::size_t{64} << 10)) {
        return small_count / 8;
    }
    return small_count;
}

class Mutator {
  public:
    explicit Mutator(std::uint64_t seed) : random_(seed) {}

    std::size_t below(std::size_t n) {
        return n == 0 ? 0 : static_cast<std::size_t>(random_() % n);
    }

    /// A byte-level corruption; returns what it did.
    std::string corrupt_bytes(std::vector<std::uint8_t>& bytes) {
        if (bytes.empty()) {
            return "empty";
        }
        switch (below(5)) {
            case 0: {
                const std::size_t flips = 1 + below(8);
                for (std::size_t i = 0; i < flips; ++i) {
                    bytes[below(bytes.size())] ^= static_cast<std::uint8_t>(1u << below(8));
                }
                return std::to_string(flips) + " bit flips";
            }
            case 1: {
                const std::size_t length = below(bytes.size());
                bytes.resize(length);
                return "truncated to " + std::to_string(length);
            }
            case 2: {
                const std::size_t swaps = 1 + below(4);
                for (std::size_t i = 0; i < swaps; ++i) {
                    std::swap(bytes[below(bytes.size())], bytes[below(bytes.size())]);
                }
                return std::to_string(swaps) + " byte swaps";
            }
            case 3: {
                // Values that stress size arithmetic, written little-endian at any offset.
                static constexpr std::uint32_t kValues[] = {0u,          1u,          0x7Fu,
                                                            0x80u,       0xFFFFu,     0x7FFFFFFFu,
                                                            0x80000000u, 0xFFFFFFFFu, 0xFFFFFFF0u};
                const std::uint32_t value = kValues[below(std::size(kValues))];
                const std::size_t offset = below(bytes.size());
                for (std::size_t k = 0; k < 4 && offset + k < bytes.size(); ++k) {
                    bytes[offset + k] = static_cast<std::uint8_t>(value >> (8 * k));
                }
                return "wrote " + std::to_string(value) + " at " + std::to_string(offset);
            }
            default: {
                const std::size_t at = below(bytes.size());
                const std::size_t length = 1 + below(16);
                if (below(2) == 0) {
                    bytes.erase(bytes.begin() + static_cast<std::ptrdiff_t>(at),
                                bytes.begin() + static_cast<std::ptrdiff_t>(
                                                    std::min(bytes.size(), at + length)));
                    return "deleted bytes at " + std::to_string(at);
                }
                bytes.insert(bytes.begin() + static_cast<std::ptrdiff_t>(at), length,
                             static_cast<std::uint8_t>(random_()));
                return "inserted bytes at " + std::to_string(at);
            }
        }
    }

    /// A structural edit somewhere in the document; returns what it did.
    std::string corrupt_json(json& document) {
        std::vector<json::json_pointer> places;
        collect(document, json::json_pointer(), places);
        const json::json_pointer target = places[below(places.size())];
        json& value = document[target];
        switch (below(5)) {
            case 0: {  // delete a key or array element
                if (target.empty()) {
                    return "nothing deleted";
                }
                json& parent = document[target.parent_pointer()];
                if (parent.is_object()) {
                    parent.erase(target.back());
                } else {
                    parent.erase(static_cast<std::size_t>(std::stoull(target.back())));
                }
                return "deleted " + target.to_string();
            }
            case 1: {  // change a number (or put one where there was none)
                static constexpr double kNumbers[] = {
                    0.0,          -1.0,         1.0,          0.5,  2.0,   3.0,   65535.0, 65536.0,
                    2147483648.0, 4294967295.0, 4294967296.0, 1e30, -1e30, 1e-30, 9.2e18};
                const double number = kNumbers[below(std::size(kNumbers))];
                const bool integral =
                    std::trunc(number) == number && number >= 0.0 && number < 1e19;
                if (integral && below(2) == 0) {
                    value = static_cast<std::uint64_t>(number);
                } else if (value.is_number() && below(3) == 0) {
                    value = value.get<double>() + number;
                } else {
                    value = number;
                }
                return "number at " + target.to_string();
            }
            case 2: {  // wrong type
                static const json kValues[] = {
                    nullptr, true, "x", json::array(), json::object(), json::array({1, 2, 3}), -7};
                value = kValues[below(std::size(kValues))];
                return "retyped " + target.to_string();
            }
            case 3: {  // swap with another value anywhere
                const json::json_pointer other = places[below(places.size())];
                if (other == target || target.to_string().rfind(other.to_string(), 0) == 0 ||
                    other.to_string().rfind(target.to_string(), 0) == 0) {
                    return "no swap";  // one contains the other
                }
                std::swap(document[target], document[other]);
                return "swapped " + target.to_string() + " and " + other.to_string();
            }
            default: {  // duplicate into an array, or copy a sibling's value
                if (value.is_array() && !value.empty()) {
                    value.push_back(value[below(value.size())]);
                    return "duplicated in " + target.to_string();
                }
                value = document[places[below(places.size())]];
                return "copied into " + target.to_string();
            }
        }
    }

  private:
    static void collect(const json& value, const json::json_pointer& at,
                        std::vector<json::json_pointer>& out) {
        out.push_back(at);
        if (value.is_object()) {
            for (const auto& [key, child] : value.items()) {
                collect(child, at / key, out);
            }
        } else if (value.is_array()) {
            for (std::size_t i = 0; i < value.size(); ++i) {
                collect(value[i], at / i, out);
            }
        }
    }

    std::mt19937_64 random_;
};

struct Tally {
    std::size_t loaded = 0;
    std::size_t rejected = 0;
};

/// Loads one corrupted file; anything but a valid scene or a luxel::Error is a failure.
void load_one(const MutationInput& input, const std::vector<std::uint8_t>& bytes,
              const std::string& what, Tally& tally) {
    try {
        const luxel::scene::Scene scene =
            luxel::scene::load_gltf_from_memory(bytes, input.name, input.base_dir);
        scene.validate();
        (void)scene.world_matrices();
        for (std::size_t i = 0; i < scene.nodes.size(); ++i) {
            (void)scene.is_dynamic(static_cast<int>(i));
        }
        // What loads must also write and load again.
        const std::vector<std::uint8_t> again =
            luxel::scene::save_gltf_to_memory(scene, luxel::scene::GltfContainer::Binary);
        (void)luxel::scene::load_gltf_from_memory(again, input.name + " (rewritten)");
        ++tally.loaded;
    } catch (const luxel::Error& e) {
        const std::string message = e.what();
        if (message.rfind(input.name, 0) != 0) {
            ADD_FAILURE() << input.name << " " << what
                          << ": error does not name the file: " << message;
        }
        ++tally.rejected;
    } catch (const std::exception& e) {
        ADD_FAILURE() << input.name << " " << what << ": not a luxel::Error: " << e.what();
    }
}

/// Prints, per input, how many cases ran and how long they took (the suite has a time budget
/// under the sanitizers; this shows where it goes).
class InputTimer {
  public:
    InputTimer(const MutationInput& input, const char* kind, const Tally& tally)
        : input_(input),
          kind_(kind),
          tally_(tally),
          before_(tally),
          start_(std::chrono::steady_clock::now()) {}
    ~InputTimer() {
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_)
                .count();
        std::printf("  %-28s %5s: %4zu cases (%4zu loaded) in %7.0f ms\n", input_.name.c_str(),
                    kind_, tally_.loaded + tally_.rejected - before_.loaded - before_.rejected,
                    tally_.loaded - before_.loaded, ms);
    }
    InputTimer(const InputTimer&) = delete;
    InputTimer& operator=(const InputTimer&) = delete;

  private:
    const MutationInput& input_;
    const char* kind_;
    const Tally& tally_;
    Tally before_;
    std::chrono::steady_clock::time_point start_;
};

/// Quiet loads: thousands of warnings about corrupted files are expected, not interesting.
class GltfMutation : public ::testing::Test {
  protected:
    void SetUp() override {
        saved_level_ = luxel::log::level();
        luxel::log::set_level(luxel::log::Level::Error);
    }
    void TearDown() override { luxel::log::set_level(saved_level_); }

  private:
    luxel::log::Level saved_level_ = luxel::log::Level::Info;
};

constexpr std::size_t kByteCasesPerInput = 600;
constexpr std::size_t kJsonCasesPerInput = 500;

TEST_F(GltfMutation, ByteCorruptionsLoadOrFailCleanly) {
    luxel::testing::TempDir dir;
    Tally tally;
    std::size_t total = 0;
    for (const MutationInput& input : mutation_inputs(dir)) {
        const InputTimer timer(input, "byte", tally);
        for (std::size_t i = 0; i < cases_for(input, kByteCasesPerInput); ++i) {
            Mutator mutator(0x6c75786c00000000ull + i);
            std::vector<std::uint8_t> bytes = input.bytes;
            const std::string what =
                "byte case " + std::to_string(i) + " (" + mutator.corrupt_bytes(bytes) + ")";
            load_one(input, bytes, what, tally);
            ++total;
        }
    }
    std::printf("byte corruptions: %zu cases, %zu loaded, %zu rejected\n", total, tally.loaded,
                tally.rejected);
    EXPECT_GT(tally.rejected, total / 2);
}

TEST_F(GltfMutation, JsonCorruptionsLoadOrFailCleanly) {
    luxel::testing::TempDir dir;
    Tally tally;
    std::size_t total = 0;
    for (const MutationInput& input : mutation_inputs(dir)) {
        luxel::testing::GlbParts parts;
        if (input.binary) {
            parts = luxel::testing::split_glb(input.bytes);
        } else {
            parts.json.assign(input.bytes.begin(), input.bytes.end());
        }
        const json original = json::parse(parts.json);
        const InputTimer timer(input, "JSON", tally);
        for (std::size_t i = 0; i < cases_for(input, kJsonCasesPerInput); ++i) {
            Mutator mutator(0x6a736f6e00000000ull + i);
            json document = original;
            std::string what = "json case " + std::to_string(i) + " (";
            // One to three edits per case: single edits mostly hit one check each.
            const std::size_t edits = 1 + mutator.below(3);
            for (std::size_t e = 0; e < edits; ++e) {
                what += mutator.corrupt_json(document) + (e + 1 < edits ? ", " : ")");
            }
            const std::string text = document.dump();
            const std::vector<std::uint8_t> bytes = input.binary
                                                        ? luxel::testing::make_glb(text, parts.bin)
                                                        : luxel::testing::bytes_of(text);
            load_one(input, bytes, what, tally);
            ++total;
        }
    }
    std::printf("JSON corruptions: %zu cases, %zu loaded, %zu rejected\n", total, tally.loaded,
                tally.rejected);
    EXPECT_GT(tally.loaded, 0u);
    EXPECT_GT(tally.rejected, 0u);
}

}  // namespace
