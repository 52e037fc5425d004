// The loading screen lights the pose the first frame shows (issue 28): luxel-sandbox's frame 0
// of a level whose animations move things at t = 0 equals, within the lighting's noise, frame 0
// of the same level with that pose baked into the file (animations sampled at t = 0 into the
// nodes, light switches into their lights' state). The same level with its animations dropped
// (the glTF rest pose) is the control: it must differ by much more, or the comparison could not
// tell the poses apart.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "luxel/runtime/image.hpp"
#include "luxel/scene/animation.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/world/animation_system.hpp"
#include "run_sandbox.hpp"
#include "temp_dir.hpp"
#include "test_paths.hpp"

namespace {

using namespace luxel;

/// `level` with its t = 0 pose written into its nodes and no animation left; the nodes that
/// were animated stay dynamic, as they were.
scene::Scene baked_at_start(scene::Scene level) {
    for (const scene::Animation& animation : level.animations) {
        for (const scene::AnimationChannel& channel : animation.channels) {
            scene::Node& node = level.nodes.at(static_cast<std::size_t>(channel.node));
            const glm::vec4 v = animation.samplers.at(static_cast<std::size_t>(channel.sampler))
                                    .sample(0.0f, channel.property);
            switch (channel.property) {
                case scene::AnimatedProperty::Translation:
                    node.translation = scene::as_vec3(v);
                    break;
                case scene::AnimatedProperty::Rotation:
                    node.rotation = scene::as_quat(v);
                    break;
                case scene::AnimatedProperty::Scale:
                    node.scale = scene::as_vec3(v);
                    break;
            }
            node.flags.dynamic = true;
        }
    }
    level.animations.clear();
    for (scene::Node& node : level.nodes) {
        const auto found = node.flags.raw.find("switch");
        if (found == node.flags.raw.end() || !found->is_object()) {
            continue;
        }
        world::LightSwitch light_switch;
        light_switch.period = found->value("period", light_switch.period);
        light_switch.on = found->value("on", light_switch.on);
        light_switch.phase = found->value("phase", light_switch.phase);
        node.flags.light_enabled = world::switch_is_on(light_switch, 0.0);
        node.flags.raw.erase("switch");
        node.flags.raw.erase("enabled");
    }
    return level;
}

Image frame_zero(const std::string& level, const luxel::testing::TempDir& out,
                 const std::string& name) {
    const std::filesystem::path dir = out / name;
    const auto result = luxel::testing::run_sandbox(
        "--gl egl --level " + level + " --frames 1 --camera fixed --size 160x120 --exr --out " +
        dir.string());
    EXPECT_EQ(result.exit_code, 0) << result.output;
    return read_exr(dir / "frame_0000.exr");
}

double rel_rmse(const Image& a, const Image& b) {
    double error = 0.0;
    double norm = 0.0;
    for (std::size_t i = 0; i < a.rgba.size() && i < b.rgba.size(); ++i) {
        if (i % 4 == 3) {
            continue;
        }
        const double d = double(a.rgba[i]) - b.rgba[i];
        error += d * d;
        norm += double(b.rgba[i]) * b.rgba[i];
    }
    return norm > 0.0 ? std::sqrt(error / norm) : 1.0;
}

class StartPose : public ::testing::TestWithParam<std::string> {};

TEST_P(StartPose, FrameZeroIsTheFrameOfTheStartPoseBakedIntoTheFile) {
    const std::string level = GetParam();
    const std::filesystem::path file =
        luxel::testing::source_dir() / "assets/levels/prepared" / (level + ".glb");
    const scene::Scene source = scene::load_gltf(file);
    ASSERT_FALSE(source.animations.empty()) << level << " must move something at t = 0";
    luxel::testing::TempDir out("luxel-start-pose");
    scene::save_gltf(baked_at_start(source), out / (level + "-posed.glb"));
    scene::Scene rest = source;
    rest.animations.clear();
    scene::save_gltf(rest, out / (level + "-rest.glb"));

    const Image played = frame_zero(level, out, "played");
    const Image posed = frame_zero((out / (level + "-posed.glb")).string(), out, "posed");
    const Image resting = frame_zero((out / (level + "-rest.glb")).string(), out, "rest");
    ASSERT_EQ(played.rgba.size(), posed.rgba.size());
    ASSERT_EQ(resting.rgba.size(), posed.rgba.size());
    const double same = rel_rmse(played, posed);
    const double control = rel_rmse(resting, posed);
    std::printf("%s frame 0 against its baked start pose: relRMSE %.2f%%; the rest pose %.2f%%\n",
                level.c_str(), 100.0 * same, 100.0 * control);
    EXPECT_LT(same, 0.02);
    EXPECT_LT(same, 0.25 * control);
}

std::string level_name(const ::testing::TestParamInfo<std::string>& param) {
    std::string name = param.param;
    std::replace(name.begin(), name.end(), '-', '_');
    return name;
}

INSTANTIATE_TEST_SUITE_P(Levels, StartPose, ::testing::Values("cornell"), level_name);

}  // namespace
