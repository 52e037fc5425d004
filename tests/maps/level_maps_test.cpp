// Every built-in prepared level through photons, AIM and CPU gather: texels agree with the
// layout luxel-prep wrote, and no texel is NaN, infinite or negative.

#include <cmath>
#include <filesystem>
#include <memory>
#include <span>
#include <string_view>

#include <gtest/gtest.h>

#include "luxel/lighting/core/cpu_gather.hpp"
#include "luxel/lighting/core/gather.hpp"
#include "luxel/runtime/clock.hpp"
#include "luxel/runtime/jobs.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/world/scene_instance.hpp"
#include "map_test_scenes.hpp"

namespace {

using namespace luxel;

class LevelMaps : public ::testing::TestWithParam<const char*> {};

bool valid(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && v.x >= 0.0f &&
           v.y >= 0.0f && v.z >= 0.0f;
}

TEST_P(LevelMaps, TexelsMatchTheLayoutAndEveryValueIsFinite) {
    luxel::testing::TracedLevel level(GetParam());
    ecs::Registry& registry = level.registry;
    JobSystem& jobs = level.jobs;
    lighting::PhotonWorld& photons = *level.photons;
    lighting::IlluminationMaps maps(registry, photons);
    maps.sync();

    // Every surface's texel count is what luxel-prep's table says: the runtime lights exactly
    // the texels the layout reserved.
    std::size_t checked = 0;
    for (std::uint32_t s = 0; s < maps.surfaces().size(); ++s) {
        const auto& info = photons.surfaces()[s];
        if (info.layout_id < 0) {
            continue;
        }
        const auto& layout = registry.get<lighting::LightmappedSurface>(info.entity).layout;
        for (const auto& entry : layout.surfaces) {
            if (entry.id == info.layout_id) {
                EXPECT_EQ(static_cast<std::int64_t>(maps.surfaces()[s].texels.texels.size()),
                          entry.texels)
                    << GetParam() << " surface " << entry.id;
                ++checked;
            }
        }
    }
    EXPECT_GT(checked, 0u);

    const auto requests = maps.aim_requests();
    for (const auto& request : requests) {
        maps.rebuild_aim(request.surface);
    }
    EXPECT_TRUE(maps.aim_requests().empty());
    double total = 0.0;
    for (const auto& page : maps.aim().pages) {
        for (const glm::vec3& texel : page.texels) {
            ASSERT_TRUE(valid(texel)) << GetParam() << " AIM";
            total += texel.x + texel.y + texel.z;
        }
    }
    EXPECT_GT(total, 0.0) << GetParam() << ": photons reached no light-mapped texel";

    lighting::CpuGatherer gatherer(photons.ray_scene(), maps.aim(), {16, 1e6f}, &jobs);
    for (const auto& request : maps.gather_requests()) {
        maps.gather(request.surface, 1u << 20, gatherer, 0.0);
    }
    EXPECT_TRUE(maps.gather_requests().empty());
    double gathered = 0.0;
    for (const auto& page : maps.iim_pages()) {
        for (const glm::vec3& texel : page.current.texels) {
            ASSERT_TRUE(valid(texel)) << GetParam() << " IIM";
            gathered += texel.x;
        }
    }
    EXPECT_GT(gathered, 0.0) << GetParam();
    std::printf("[ figures  ] %s: %zu surfaces, %llu AIM texels, %llu texels gathered\n",
                GetParam(), maps.surfaces().size(),
                static_cast<unsigned long long>(maps.counters().aim_texels),
                static_cast<unsigned long long>(maps.counters().texels_gathered));
}

INSTANTIATE_TEST_SUITE_P(BuiltInLevels, LevelMaps,
                         ::testing::Values("cornell", "two-rooms", "caustics", "sandbox",
                                           "furnace"),
                         [](const auto& param_info) {
                             std::string name = param_info.param;
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });

TEST(IlluminationMaps, GatherPassesRunInSlicesAndFadeIn) {
    luxel::testing::PlaneWorld world(1.0f, 0.1f, 16, glm::vec3(0.5f));
    ASSERT_EQ(world.maps->surfaces()[0].texels.texels.size(), 100u);
    lighting::CpuGatherer gatherer(world.photons->ray_scene(), world.maps->aim(), {4, 1e6f});
    auto requests = world.maps->gather_requests();
    ASSERT_EQ(requests.size(), 1u);
    EXPECT_EQ(world.maps->gather(0, 30, gatherer, 1.0), 30u);
    EXPECT_EQ(world.maps->gather_requests().size(), 1u) << "a pass in progress stays queued";
    EXPECT_EQ(world.maps->gather(0, 100, gatherer, 1.0), 70u);
    EXPECT_TRUE(world.maps->gather_requests().empty());
    EXPECT_EQ(world.maps->counters().gather_passes, 1u);
    const auto dirty = world.maps->iim_pages()[0].current.changes_since(0).rect;
    EXPECT_GT(dirty.width, 0);
    EXPECT_LE(dirty.width, 14);  // the chart and its two padding rings, not the page
}

/// A gatherer that knows the answer: irradiance 1 W/m^2 left of x = 2.5 m, 4 right of it.
class TwoValueGatherer : public lighting::IrradianceGatherer {
  public:
    [[nodiscard]] std::string_view name() const override { return "two values"; }
    void gather(std::span<const lighting::GatherTexel> texels,
                std::span<glm::vec3> irradiance) override {
        for (std::size_t i = 0; i < texels.size() && i < irradiance.size(); ++i) {
            irradiance[i] = glm::vec3(texels[i].position.x < 2.5f ? 1.0f : 4.0f);
        }
    }
};

/// A 0.4 m square at y = 0 whose 4 x 4 texels (0.1 m) start at page texel (left, 2).
scene::Primitive square_at(float x0, int left, int page_size) {
    scene::Primitive p;
    p.material = 0;
    for (int j = 0; j <= 1; ++j) {
        for (int i = 0; i <= 1; ++i) {
            p.positions.emplace_back(x0 + 0.4f * static_cast<float>(i), 0.0f,
                                     0.4f * static_cast<float>(j));
            p.normals.emplace_back(0.0f, 1.0f, 0.0f);
            p.texcoords1.emplace_back(
                (static_cast<float>(left) + 4.0f * static_cast<float>(i)) /
                    static_cast<float>(page_size),
                (2.0f + 4.0f * static_cast<float>(j)) / static_cast<float>(page_size));
        }
    }
    p.indices = {0, 2, 1, 1, 2, 3};
    return p;
}

TEST(IlluminationMaps, PaddingFillsTwoRingsAndLeavesANeighboursFirstRingToIt) {
    // Two squares on one 20-texel page: A's texels at x 2..5, B's at 8..11, two texels apart
    // as luxel-prep's default padding of 1 packs them; right of B the page is free. The first
    // ring serves bilinear lookups, the second bicubic ones (docs/METHOD.md §8.5) where the
    // chart has room for it; texel 7, two from A but next to B, belongs to B's first ring.
    constexpr int kPage = 20;
    auto level = std::make_shared<scene::Scene>();
    scene::Material material;
    material.base_color = glm::vec4(glm::vec3(0.5f), 1.0f);
    level->materials.push_back(material);
    level->meshes.push_back({"A", {square_at(0.0f, 2, kPage)}});
    level->meshes.push_back({"B", {square_at(5.0f, 8, kPage)}});
    ecs::Registry registry;
    ecs::TransformSystem transforms(registry);
    for (const int mesh : {0, 1}) {
        const ecs::Entity entity = registry.create();
        registry.emplace<scene::MeshInstance>(entity, level, mesh);
        scene::LightmapLayout layout;
        layout.texel_size = 0.1f;
        layout.page_size = kPage;
        scene::LightmapSurface surface;
        surface.id = 0;
        surface.primitive = 0;
        surface.rect = {mesh == 0 ? 2 : 8, 2, 4, 4};
        surface.charts = {surface.rect};
        surface.area = 0.16;
        surface.texels = 16;
        layout.surfaces.push_back(surface);
        registry.emplace<lighting::LightmappedSurface>(entity, layout);
        registry.emplace<ecs::Transform>(entity, ecs::Transform{});
    }
    transforms.update();
    lighting::PhotonWorld photons(registry);
    photons.sync();
    lighting::IlluminationMaps maps(registry, photons);
    maps.sync();
    TwoValueGatherer gatherer;
    for (const auto& request : maps.gather_requests()) {
        maps.gather(request.surface, 1u << 20, gatherer, 0.0);
    }
    const lighting::RadiancePage& page = maps.iim_pages()[0].current;
    const glm::vec3 a = page.at(3, 3);
    const glm::vec3 b = page.at(9, 3);
    ASSERT_GT(a.x, 0.0f);
    ASSERT_NEAR(b.x, 4.0f * a.x, 1e-4f * b.x);
    for (int y = 2; y <= 5; ++y) {
        EXPECT_EQ(page.at(1, y), a) << "A's first ring, row " << y;
        EXPECT_EQ(page.at(0, y), a) << "A's second ring, row " << y;
        EXPECT_EQ(page.at(6, y), a) << "A's first ring towards B, row " << y;
        EXPECT_EQ(page.at(7, y), b) << "B's first ring, not A's second, row " << y;
        EXPECT_EQ(page.at(12, y), b) << "B's first ring, row " << y;
        EXPECT_EQ(page.at(13, y), b) << "B's second ring, row " << y;
        EXPECT_EQ(page.at(14, y), glm::vec3(0.0f)) << "no third ring, row " << y;
    }
    EXPECT_EQ(page.at(3, 0), a);  // rings above the charts too
    EXPECT_EQ(page.at(9, 7), b);  // and below
    EXPECT_EQ(page.at(9, 8), glm::vec3(0.0f));
}

// Every mesh a level places is a photon-world surface and each one added is a geometry change;
// finding the light-mapped surfaces near each change once compared every change with every
// surface, light-mapped or not, so 300,000 plain meshes took minutes to load (the hostile
// corpus' nodes-300k-one-mesh). Only surfaces with texels are compared now.
TEST(IlluminationMaps, ManyMeshesWithoutLightMapsSyncInLinearTime) {
    constexpr int kMeshes = 100'000;
    ecs::Registry registry;
    const auto plane = luxel::testing::lightmapped_plane(1.0f, 1, 0.1f, 64, glm::vec3(0.5f));
    for (int i = 0; i < kMeshes; ++i) {
        const ecs::Entity entity = registry.create();
        registry.emplace<scene::MeshInstance>(entity, plane, 0);  // no LightmappedSurface
        registry.emplace<ecs::Transform>(entity, ecs::Transform{});
    }
    ecs::TransformSystem transforms(registry);
    transforms.update();
    lighting::PhotonWorld photons(registry);
    photons.sync();
    ASSERT_GE(photons.geometry_changes().size(), static_cast<std::size_t>(kMeshes));
    Stopwatch clock;
    lighting::IlluminationMaps maps(registry, photons);
    // 10^10 box tests before; a pass over the surfaces now (about 0.1 s).
    EXPECT_LT(clock.elapsed_ms(), 5000.0);
    EXPECT_EQ(maps.surfaces().size(), static_cast<std::size_t>(kMeshes));
}

}  // namespace
