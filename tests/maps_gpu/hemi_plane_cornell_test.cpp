// The GPU gather against ray-traced references on texels of the prepared Cornell box, whose AIM
// pages hold a smooth synthetic radiance.
//
// The hemi-plane sees only the part of the hemisphere its plane covers (F(a) of the
// cosine-weighted whole) and assumes the rest looks the same. So: (1) at the default a = 2 it
// must equal a ray-traced estimate of that same quantity (rays restricted to the plane's view,
// divided by F(a)) within 2%: that checks the rasterisation, the weights and the reduction;
// (2) with a plane wide enough to cover the hemisphere (a = 8, F = 0.987) it must equal
// CpuGatherer, the other backend of the contract, within 2%; (3) at a = 2 its difference from
// CpuGatherer is the method's own error, reported and bounded.

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "gather_scenes.hpp"
#include "luxel/lighting/core/cpu_gather.hpp"
#include "luxel/lighting/core/halton.hpp"
#include "luxel/lighting/core/light_source.hpp"
#include "luxel/lighting/gpu/hemi_plane_gatherer.hpp"
#include "luxel/lighting/gpu/hemi_plane_geometry.hpp"
#include "luxel/runtime/jobs.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;

struct Errors {
    double worst = 0.0;      ///< largest per-texel, per-channel relative error
    double aggregate = 0.0;  ///< sum |gpu - ref| / sum ref over all texels and channels
};

Errors compare(const std::vector<glm::vec3>& gpu, const std::vector<glm::vec3>& reference) {
    Errors errors;
    double difference = 0.0;
    double total = 0.0;
    for (std::size_t i = 0; i < gpu.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            const auto g = static_cast<double>(gpu[i][c]);
            const auto r = static_cast<double>(reference[i][c]);
            errors.worst = std::max(errors.worst, std::abs(g - r) / r);
            difference += std::abs(g - r);
            total += r;
        }
    }
    errors.aggregate = difference / total;
    return errors;
}

/// Irradiance as the hemi-plane defines it, by ray tracing: cosine-weighted Halton directions,
/// only those the plane of half-width `a` sees (in the gatherer's own frame), pi * mean(L) / F(a).
glm::vec3 plane_restricted_reference(const test::GatherLevel& level, const GatherTexel& texel,
                                     float a, std::uint32_t rays) {
    const glm::vec3 n = glm::normalize(texel.normal);
    const HemiPlaneFrame frame = hemi_plane_frame(n);
    const glm::vec3 origin = offset_ray_origin(texel.position, n);
    glm::dvec3 sum(0.0);
    for (std::uint32_t i = 0; i < rays; ++i) {
        const glm::vec3 d = cosine_direction(n, halton2(i));
        const float z = glm::dot(d, frame.forward);
        if (std::abs(glm::dot(d, frame.right)) >= a * z ||
            std::abs(glm::dot(d, frame.up)) >= a * z) {
            continue;
        }
        const auto hit = level.scene().intersect(origin, d);
        if (hit && glm::dot(hit->geometric_normal, d) < 0.0f) {
            sum += glm::dvec3(level.atlas.sample(hit->surface, hit->lightmap_uv));
        }
    }
    return glm::vec3(sum * glm::pi<double>() / static_cast<double>(rays) /
                     hemi_plane_coverage(static_cast<double>(a)));
}

/// The plane alone, as the paper has it: no horizon rays (the band it misses assumed to look
/// like what it sees) and no turn per pass.
HemiPlaneSettings plane_only() {
    HemiPlaneSettings settings;
    settings.horizon_rays = 0;
    settings.rotate = false;
    return settings;
}

class HemiPlaneCornell : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        level_ = std::make_unique<test::GatherLevel>("prepared/cornell");
        texels_ = level_->texels(50);
        JobSystem jobs(2);
        CpuGatherer cpu(level_->scene(), level_->atlas, {4096}, &jobs);
        cpu_ = std::vector<glm::vec3>(texels_.size());
        cpu.gather(texels_, cpu_);
    }
    static void TearDownTestSuite() { level_.reset(); }

    void SetUp() override {
        ASSERT_FALSE(level_->atlas.pages.empty()) << "cornell.glb has no light-map layout";
        ASSERT_GE(texels_.size(), 40u);
        for (const glm::vec3& e : cpu_) {
            ASSERT_GT(glm::min(e.x, glm::min(e.y, e.z)), 0.0f) << "a texel sees no light";
        }
        context_ = test::make_gl_context();
    }

    std::vector<glm::vec3> gpu_gather(const HemiPlaneSettings& settings) const {
        HemiPlaneGatherer gpu(level_->scene(), level_->atlas, settings);
        std::vector<glm::vec3> e(texels_.size());
        gpu.gather(texels_, e);
        return e;
    }

    static inline std::unique_ptr<test::GatherLevel> level_;
    static inline std::vector<GatherTexel> texels_;
    static inline std::vector<glm::vec3> cpu_;
    std::unique_ptr<GlContext> context_;
};

TEST_F(HemiPlaneCornell, DefaultPlaneMatchesRaysRestrictedToItsView) {
    // Per-texel differences are the plane's pixels: a pixel at the axis spans 3.6 degrees at
    // 64 pixels, and wall edges and the (black) lamp fall across pixels. They halve with each
    // doubling of the resolution; the aggregate is small at both.
    const HemiPlaneSettings defaults;
    std::vector<glm::vec3> reference;
    for (const GatherTexel& texel : texels_) {
        reference.push_back(plane_restricted_reference(*level_, texel, defaults.half_width, 16384));
    }
    for (const auto& [resolution, bound] : {std::pair{64, 0.04f}, std::pair{128, 0.02f}}) {
        HemiPlaneSettings settings = plane_only();
        settings.resolution = resolution;
        const std::vector<glm::vec3> gpu = gpu_gather(settings);
        for (std::size_t i = 0; i < gpu.size(); ++i) {
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(gpu[i][c], reference[i][c], bound * reference[i][c])
                    << resolution << " pixels, texel " << i << " channel " << c;
            }
        }
        const Errors errors = compare(gpu, reference);
        std::printf("a = 2, %d pixels vs plane-restricted rays: max %.4f, aggregate %.4f\n",
                    resolution, errors.worst, errors.aggregate);
        RecordProperty("max_relative_error_" + std::to_string(resolution),
                       std::to_string(errors.worst));
        EXPECT_LT(errors.aggregate, 0.01);
    }
}

TEST_F(HemiPlaneCornell, WidePlaneMatchesTheCpuGatherWithinTwoPercent) {
    HemiPlaneSettings settings = plane_only();
    settings.half_width = 8.0f;
    settings.resolution = 512;  // the same pixel size near the axis as 64 pixels at a = 1
    settings.texels_per_batch = 16;
    const std::vector<glm::vec3> gpu = gpu_gather(settings);
    for (std::size_t i = 0; i < gpu.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(gpu[i][c], cpu_[i][c], 0.02f * cpu_[i][c])
                << "texel " << i << " at (" << texels_[i].position.x << ", "
                << texels_[i].position.y << ", " << texels_[i].position.z << ") channel " << c;
        }
    }
    const Errors errors = compare(gpu, cpu_);
    std::printf("a = 8 vs CpuGatherer: max %.4f, aggregate %.4f\n", errors.worst, errors.aggregate);
    RecordProperty("max_relative_error", std::to_string(errors.worst));
    EXPECT_LT(errors.aggregate, 0.02);
}

TEST_F(HemiPlaneCornell, DefaultPlaneErrorAgainstTheCpuGatherIsTheHorizonsShare) {
    // What a = 2 misses is the horizon band (1 - F(2) = 17% of the cosine-weighted
    // hemisphere), where a Cornell texel sees walls at grazing angles rather than the far side
    // of the box: the error is the method's, and bounded by that share.
    const std::vector<glm::vec3> gpu = gpu_gather(plane_only());
    const Errors errors = compare(gpu, cpu_);
    std::printf("a = 2 vs CpuGatherer: max %.4f, aggregate %.4f\n", errors.worst, errors.aggregate);
    RecordProperty("max_relative_error", std::to_string(errors.worst));
    EXPECT_LT(errors.worst, 1.0 - hemi_plane_coverage(2.0));
    EXPECT_LT(errors.aggregate, 0.05);
}

TEST_F(HemiPlaneCornell, WithTheHorizonRaysPassesConvergeToTheCpuGather) {
    // The default gatherer: the plane turned anew each pass and the band it misses traced by
    // 16 CPU rays. Averaged over passes it must agree with a 65,536-ray CPU gather of the same
    // AIM within 2% on every texel (in the open, beside the walls, under the lamp's hot spot);
    // one pass alone is noisier, the plane alone biased (the test above).
    JobSystem jobs(2);
    CpuGatherer dense(level_->scene(), level_->atlas, {65536}, &jobs);
    std::vector<glm::vec3> reference(texels_.size());
    dense.gather(texels_, reference);
    HemiPlaneGatherer gpu(level_->scene(), level_->atlas, HemiPlaneSettings{});
    EXPECT_TRUE(gpu.refines());
    constexpr std::uint32_t kPasses = 32;
    std::vector<GatherTexel> texels = texels_;
    std::vector<glm::vec3> pass(texels.size());
    std::vector<glm::vec3> first;
    std::vector<glm::vec3> mean(texels.size(), glm::vec3(0.0f));
    for (std::uint32_t p = 0; p < kPasses; ++p) {
        for (GatherTexel& texel : texels) {
            texel.pass = p;
        }
        gpu.gather(texels, pass);
        if (p == 0) {
            first = pass;
        }
        for (std::size_t i = 0; i < texels.size(); ++i) {
            mean[i] += pass[i] / static_cast<float>(kPasses);
        }
    }
    EXPECT_EQ(gpu.stats().horizon_rays, kPasses * texels.size() * 16u);
    const Errors one = compare(first, reference);
    const Errors averaged = compare(mean, reference);
    const Errors plane = compare(gpu_gather(plane_only()), reference);
    std::printf(
        "a = 2 with horizon rays vs 65,536 CPU rays: one pass max %.4f aggregate %.4f; "
        "%u passes max %.4f aggregate %.4f; the plane alone max %.4f aggregate %.4f\n",
        one.worst, one.aggregate, kPasses, averaged.worst, averaged.aggregate, plane.worst,
        plane.aggregate);
    for (std::size_t i = 0; i < mean.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(mean[i][c], reference[i][c], 0.02f * reference[i][c])
                << "texel " << i << " at (" << texels_[i].position.x << ", "
                << texels_[i].position.y << ", " << texels_[i].position.z << ") channel " << c;
        }
    }
    EXPECT_LT(averaged.aggregate, 0.5 * plane.aggregate);
}

}  // namespace
