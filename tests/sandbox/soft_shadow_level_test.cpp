// A level's light with a radius in the main job (issue 26): cornell with its lamp made an 8 cm
// sphere (extras.luxel.light_radius, as a level designer would write it) draws its direct light
// through the soft-shadow pass, which report.json times; `--soft-shadows off` draws it with hard
// shadows exactly as the level without a radius draws.

#include <cstdio>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "luxel/runtime/image.hpp"
#include "luxel/scene/gltf.hpp"
#include "run_sandbox.hpp"
#include "temp_dir.hpp"
#include "test_paths.hpp"

namespace {

using namespace luxel;

struct SandboxRun {
    Image direct;
    nlohmann::json report;
};

/// Frame 0's direct term of `level` (no warm-up: the direct light needs none) and the report of
/// three frames (the passes' timer queries answer a frame late).
SandboxRun direct_frame(const std::string& level, const std::string& flags,
                        const luxel::testing::TempDir& out, const std::string& name) {
    const std::filesystem::path dir = out / name;
    const auto result = luxel::testing::run_sandbox(
        "--gl egl --level " + level +
        " --frames 3 --camera fixed --size 320x240 --terms direct --warm-up-ms 0 --aa off --exr " +
        flags + " --out " + dir.string());
    EXPECT_EQ(result.exit_code, 0) << result.output;
    SandboxRun run;
    run.direct = read_exr(dir / "frame_0000.exr");
    std::ifstream in(dir / "report.json");
    EXPECT_TRUE(in.good()) << name;
    if (in.good()) {
        run.report = nlohmann::json::parse(in);
    }
    return run;
}

int differing_pixels(const Image& a, const Image& b) {
    int differing = 0;
    for (int y = 0; y < a.height && y < b.height; ++y) {
        for (int x = 0; x < a.width && x < b.width; ++x) {
            differing += a.pixel(x, y) != b.pixel(x, y) ? 1 : 0;
        }
    }
    return differing;
}

TEST(SoftShadowLevel, ALampWithARadiusCastsSoftShadowsInTheMainJob) {
    const std::filesystem::path file =
        luxel::testing::source_dir() / "assets/levels/prepared/cornell.glb";
    scene::Scene level = scene::load_gltf(file);
    int lamps = 0;
    for (scene::Node& node : level.nodes) {
        if (node.light >= 0) {
            node.flags.light_radius = 0.08f;  // 10 cm under the ceiling: a bulb that fits
            ++lamps;
        }
    }
    ASSERT_EQ(lamps, 1);
    luxel::testing::TempDir out("luxel-soft-level");
    const std::filesystem::path soft_level = out / "cornell-bulb.glb";
    scene::save_gltf(level, soft_level);

    const SandboxRun soft = direct_frame(soft_level.string(), "", out, "soft");
    const SandboxRun hard = direct_frame(soft_level.string(), "--soft-shadows off", out, "hard");
    const SandboxRun point = direct_frame(file.string(), "", out, "point");
    ASSERT_EQ(soft.direct.width, 320);
    ASSERT_EQ(hard.direct.width, 320);
    ASSERT_EQ(point.direct.width, 320);

    const auto soft_ms = [](const nlohmann::json& report) {
        const auto& passes = report.at("pass_ms");
        return passes.contains("soft_shadows")
                   ? passes.at("soft_shadows").at("median").get<double>()
                   : -1.0;
    };
    const int softened = differing_pixels(soft.direct, hard.direct);
    std::printf("[ figures  ] pixels the sphere's penumbrae changed: %d of %d; soft pass %.2f ms\n",
                softened, 320 * 240, soft_ms(soft.report));
    // The cube's and the sphere's shadows get penumbrae: a band of pixels changes, not the frame.
    EXPECT_GT(softened, 100);
    EXPECT_LT(softened, 320 * 240 / 2);
    EXPECT_EQ(differing_pixels(hard.direct, point.direct), 0)
        << "--soft-shadows off draws the sphere as the point it was";
    EXPECT_GT(soft_ms(soft.report), 0.0);
    EXPECT_EQ(soft_ms(hard.report), 0.0);
    EXPECT_EQ(soft_ms(point.report), 0.0);
}

}  // namespace
