// FeaturePlan: which passes a scene needs, and why.

#include <algorithm>
#include <string>

#include <gtest/gtest.h>

#include "luxel/lighting/core/feature_plan.hpp"

namespace {

using namespace luxel::lighting;

/// A lit, light-mapped scene with one moving object, not converged, no generator.
SceneCensus busy_scene() {
    SceneCensus c;
    c.lights_enabled = 2;
    c.lights_total = 2;
    c.lightmapped_surfaces = 40;
    c.dynamic_objects = 3;
    c.moving_objects = 1;
    c.specular_materials = 0;
    c.converged = false;
    return c;
}

bool contains(const std::string& text, const std::string& word) {
    return text.find(word) != std::string::npos;
}

TEST(FeaturePlan, IrradianceProbesOnlyForReceiversWithoutALightMapInALitMappedScene) {
    SceneCensus c = busy_scene();
    // Every mesh light-mapped: no probes.
    EXPECT_FALSE(FeaturePlan::from(c).irradiance_probes());
    EXPECT_TRUE(contains(FeaturePlan::from(c).reason(Pass::IrradianceProbes), "no receiver needs"));
    c.unmapped_receivers = 2;
    c.probes_pending = true;
    const FeaturePlan on = FeaturePlan::from(c);
    EXPECT_TRUE(on.irradiance_probes());
    EXPECT_TRUE(contains(on.reason(Pass::IrradianceProbes), "2 receivers without a light map"))
        << on.reason(Pass::IrradianceProbes);
    // Converged and at rest, the probes stay for the frame (nothing is gathered: no units).
    c.moving_objects = 0;
    c.converged = true;
    c.probes_pending = false;
    EXPECT_TRUE(FeaturePlan::from(c).irradiance_probes());
    EXPECT_FALSE(FeaturePlan::from(c).any_tracing());
    // Nothing to gather from, or no light: none.
    SceneCensus unmapped = c;
    unmapped.lightmapped_surfaces = 0;
    EXPECT_FALSE(FeaturePlan::from(unmapped).irradiance_probes());
    SceneCensus dark = c;
    dark.lights_enabled = 0;
    EXPECT_FALSE(FeaturePlan::from(dark).irradiance_probes());
}

TEST(FeaturePlan, NoGeneratorMeansNoCausticPhotonsBuffersOrFilter) {
    const FeaturePlan plan = FeaturePlan::from(busy_scene());
    EXPECT_FALSE(plan.caustics());
    EXPECT_FALSE(plan.caustic_filter());
    EXPECT_FALSE(plan.caustic_data());
    EXPECT_TRUE(contains(plan.reason(Pass::Caustics), "generator")) << plan.reason(Pass::Caustics);
    EXPECT_TRUE(contains(plan.reason(Pass::CausticFilter), "generator"));
    // The rest of a busy lit scene is on.
    EXPECT_TRUE(plan.photon_tracing());
    EXPECT_TRUE(plan.selective_probes());
    EXPECT_TRUE(plan.aim());
    EXPECT_TRUE(plan.iim_gather());
    EXPECT_TRUE(plan.shadows());
    EXPECT_TRUE(plan.direct());
    EXPECT_FALSE(plan.specular());
    EXPECT_TRUE(contains(plan.reason(Pass::Specular), "specular"));
}

TEST(FeaturePlan, AddingAGeneratorAtRunTimeTurnsCausticsOn) {
    const FeaturePlan before = FeaturePlan::from(busy_scene());
    SceneCensus c = busy_scene();
    c.caustic_generators = 1;
    const FeaturePlan after = FeaturePlan::from(c);
    EXPECT_TRUE(after.caustics());
    EXPECT_TRUE(after.caustic_filter());
    EXPECT_TRUE(contains(after.reason(Pass::Caustics), "1 caustic generator"));
    const std::vector<Pass> changed = after.changed_from(before);
    EXPECT_EQ(changed, (std::vector<Pass>{Pass::Caustics, Pass::CausticFilter}));
    // And removing it turns them off again.
    EXPECT_EQ(before.changed_from(after), changed);
    EXPECT_TRUE(after.changed_from(after).empty());
}

TEST(FeaturePlan, StaticConvergedSceneTracesAndGathersNothing) {
    SceneCensus c = busy_scene();
    c.dynamic_objects = 0;
    c.moving_objects = 0;
    c.caustic_generators = 2;
    c.specular_materials = 1;
    c.converged = false;
    const FeaturePlan converging = FeaturePlan::from(c);
    EXPECT_TRUE(converging.photon_tracing());
    EXPECT_FALSE(converging.selective_probes());  // nothing can invalidate groups unseen
    EXPECT_TRUE(converging.any_tracing());
    c.converged = true;
    const FeaturePlan plan = FeaturePlan::from(c);
    EXPECT_FALSE(plan.any_tracing());
    for (const Pass pass :
         {Pass::PhotonTracing, Pass::SelectiveProbes, Pass::Caustics, Pass::Aim, Pass::IimGather}) {
        EXPECT_FALSE(plan.enabled(pass)) << name(pass);
    }
    EXPECT_TRUE(contains(plan.reason(Pass::PhotonTracing), "converged"));
    // What is drawn every frame stays: shadows, direct, the specular term, the traced caustics.
    EXPECT_TRUE(plan.shadows());
    EXPECT_TRUE(plan.direct());
    EXPECT_TRUE(plan.specular());
    EXPECT_TRUE(plan.caustic_filter());
    EXPECT_EQ(plan.active_count(), 4U);
}

TEST(FeaturePlan, DynamicObjectsAtRestAfterConvergenceAreLikeStatic) {
    SceneCensus c = busy_scene();
    c.moving_objects = 0;
    c.converged = true;
    const FeaturePlan rest = FeaturePlan::from(c);
    EXPECT_FALSE(rest.any_tracing());
    EXPECT_TRUE(contains(rest.reason(Pass::Aim), "at rest"));
    // One of them moves: tracing and probing resume.
    c.moving_objects = 1;
    const FeaturePlan moving = FeaturePlan::from(c);
    EXPECT_TRUE(moving.photon_tracing());
    EXPECT_TRUE(moving.selective_probes());
    EXPECT_TRUE(contains(moving.reason(Pass::PhotonTracing), "1 object moving"));
}

TEST(FeaturePlan, NoLightMeansNoLightingWork) {
    SceneCensus c = busy_scene();
    c.caustic_generators = 1;
    c.specular_materials = 3;
    c.lights_enabled = 0;  // two lights, both switched off
    const FeaturePlan off = FeaturePlan::from(c);
    EXPECT_EQ(off.active_count(), 0U);
    EXPECT_TRUE(contains(off.reason(Pass::Direct), "none of the 2 lights is enabled"));
    c.lights_total = 0;
    const FeaturePlan none = FeaturePlan::from(c);
    EXPECT_EQ(none.active_count(), 0U);
    EXPECT_TRUE(contains(none.reason(Pass::PhotonTracing), "no light"));
    // A default plan is the empty scene's.
    EXPECT_EQ(FeaturePlan{}.active_count(), 0U);
}

TEST(FeaturePlan, MapsStillHoldingLightAreClearedAfterTheLastLightGoesOff) {
    SceneCensus c = busy_scene();
    c.lights_enabled = 0;
    c.maps_pending = true;
    const FeaturePlan clearing = FeaturePlan::from(c);
    EXPECT_FALSE(clearing.photon_tracing());
    EXPECT_TRUE(clearing.aim());
    EXPECT_TRUE(clearing.iim_gather());
    EXPECT_TRUE(contains(clearing.reason(Pass::Aim), "clearing"));
    EXPECT_FALSE(clearing.direct());
    // Once cleared, nothing runs.
    c.maps_pending = false;
    EXPECT_FALSE(FeaturePlan::from(c).aim());
    EXPECT_FALSE(FeaturePlan::from(c).iim_gather());
}

TEST(FeaturePlan, NoLightMappedSurfaceMeansNoGlobalPhotonsAimOrIim) {
    SceneCensus c = busy_scene();
    c.lightmapped_surfaces = 0;
    c.caustic_generators = 1;
    const FeaturePlan plan = FeaturePlan::from(c);
    EXPECT_FALSE(plan.photon_tracing());
    EXPECT_FALSE(plan.selective_probes());
    EXPECT_FALSE(plan.aim());
    EXPECT_FALSE(plan.iim_gather());
    EXPECT_TRUE(contains(plan.reason(Pass::Aim), "light-mapped surface"));
    // Caustics are splatted on screen, not into light maps: they stay.
    EXPECT_TRUE(plan.caustics());
    EXPECT_TRUE(plan.direct());
}

TEST(FeaturePlan, StaticGeometryEditsNeedProbes) {
    SceneCensus c = busy_scene();
    c.dynamic_objects = 0;
    c.moving_objects = 0;
    c.converged = true;
    c.geometry_changes = 1;
    const FeaturePlan plan = FeaturePlan::from(c);
    EXPECT_TRUE(plan.photon_tracing());
    EXPECT_TRUE(plan.selective_probes());
}

TEST(FeaturePlan, DescribeListsEveryPassWithItsStateAndReason) {
    SceneCensus c = busy_scene();
    c.caustic_generators = 0;
    const FeaturePlan plan = FeaturePlan::from(c);
    const std::string table = plan.describe();
    EXPECT_EQ(static_cast<std::size_t>(std::count(table.begin(), table.end(), '\n')),
              kPassCount + 1);
    for (std::size_t p = 0; p < kPassCount; ++p) {
        const Pass pass = static_cast<Pass>(p);
        EXPECT_TRUE(contains(table, std::string(name(pass)))) << name(pass);
        EXPECT_TRUE(contains(table, plan.reason(pass)));
        EXPECT_FALSE(plan.reason(pass).empty());
    }
    EXPECT_TRUE(contains(table, "caustics          off    no caustic generator"));
    EXPECT_TRUE(contains(table, "direct            on     2 lights"));
}

TEST(FeaturePlan, IsDeterministic) {
    SceneCensus c = busy_scene();
    c.caustic_generators = 3;
    EXPECT_EQ(FeaturePlan::from(c), FeaturePlan::from(c));
    EXPECT_EQ(FeaturePlan::from(c).census(), c);
}

}  // namespace
