// The irradiance probes: their spherical harmonics against closed forms, the octahedral map,
// the grid over a level, a closed box of constant radiance, light kept out by a 10 cm wall,
// and probe rays passing through geometry that has no light map.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "cube_scene.hpp"
#include "luxel/lighting/core/cpu_gather.hpp"
#include "luxel/lighting/core/irradiance_probes.hpp"
#include "luxel/lighting/core/octahedral.hpp"
#include "luxel/runtime/jobs.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;

/// `n` directions evenly over the sphere (spherical Fibonacci).
std::vector<glm::vec3> sphere_directions(int n) {
    std::vector<glm::vec3> out;
    for (int i = 0; i < n; ++i) {
        const float z = 1.0f - (2.0f * static_cast<float>(i) + 1.0f) / static_cast<float>(n);
        const float r = std::sqrt(1.0f - z * z);
        const float phi = glm::two_pi<float>() * std::fmod(static_cast<float>(i) * 0.618034f, 1.0f);
        out.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
    }
    return out;
}

/// Radiance `radiance(d)` projected onto the nine functions by quadrature.
template <class Radiance>
ShRgb project(const Radiance& radiance) {
    const std::vector<glm::vec3> directions = sphere_directions(20000);
    ShRgb sh;
    const float weight = 4.0f * glm::pi<float>() / static_cast<float>(directions.size());
    for (const glm::vec3& d : directions) {
        const ShBasis y = sh_basis(d);
        for (std::size_t i = 0; i < kShCoefficients; ++i) {
            sh.c[i] += radiance(d) * (y[i] * weight);
        }
    }
    return sh;
}

TEST(IrradianceProbes, ShOfConstantRadianceGivesPiLForEveryNormal) {
    const glm::vec3 l(0.5f, 1.0f, 2.0f);
    const ShRgb e = convolve_cosine(project([&](const glm::vec3&) { return l; }));
    for (const glm::vec3& n : sphere_directions(50)) {
        const glm::vec3 got = evaluate(e, n);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(got[c], glm::pi<float>() * l[c], 1e-3f * l[c]) << c;
        }
    }
}

TEST(IrradianceProbes, ShOfAHemisphereSkyMatchesItsClosedForm) {
    // L = 1 from the upper hemisphere (z > 0): E(n) = pi (1 + cos theta) / 2 for a normal at
    // angle theta from +z. Band 2 holds it to within ~4% of pi over the sphere (Ramamoorthi &
    // Hanrahan's bound for any lighting is 9%; a hemisphere is far from the worst).
    const ShRgb e = convolve_cosine(
        project([](const glm::vec3& d) { return d.z > 0.0f ? glm::vec3(1.0f) : glm::vec3(0.0f); }));
    for (const glm::vec3& n : sphere_directions(200)) {
        const float expected = glm::pi<float>() * (1.0f + n.z) * 0.5f;
        EXPECT_NEAR(evaluate(e, n).x, expected, 0.04f * glm::pi<float>()) << n.z;
    }
}

TEST(IrradianceProbes, OctahedralMapRoundTrips) {
    for (const glm::vec3& d : sphere_directions(2000)) {
        const glm::vec2 p = octahedral_encode(d);
        EXPECT_LE(std::abs(p.x) + 0.0f, 1.0f);
        EXPECT_LE(std::abs(p.y) + 0.0f, 1.0f);
        const glm::vec3 back = octahedral_decode(p);
        EXPECT_NEAR(glm::dot(back, d), 1.0f, 1e-5f);
    }
    // The poles and the folds.
    EXPECT_NEAR(octahedral_decode(octahedral_encode({0, 0, -1})).z, -1.0f, 1e-6f);
    EXPECT_NEAR(octahedral_decode(octahedral_encode({1, 0, 0})).x, 1.0f, 1e-6f);
}

/// How far one probe's irradiance is from the exact integral of `radiance`, over normals whose
/// exact irradiance is at least 3% of the brightest (the skinned figure's faces towards the
/// open side of its room are at 4%; below, a relative error means little on a screen).
struct BasisError {
    double rms = 0.0;
    double worst = 0.0;
    int normals = 0;
};

template <class Radiance>
BasisError basis_error(ProbeBasis basis, const Radiance& radiance) {
    const ProbeRayTracer tracer = [&](const glm::vec3&, std::span<const glm::vec3> directions,
                                      std::span<ProbeRay> rays, std::uint32_t) {
        for (std::size_t i = 0; i < directions.size(); ++i) {
            rays[i] = {radiance(directions[i]), 1.0f, true, false};
        }
    };
    AxisBox level;
    level.add({0.0f, 0.0f, 0.0f});
    level.add({1.0f, 1.0f, 1.0f});
    IrradianceProbeSettings settings;
    settings.basis = basis;
    settings.rays_per_probe = 8192;  // 4 passes: the sampling noise well under the basis' error
    IrradianceProbes probes(fit_probe_grid(level, 1.0f, 4096), settings);
    while (probes.pending() > 0) {
        probes.gather(64, tracer, nullptr);
    }
    const std::vector<glm::vec3> quadrature = sphere_directions(40000);
    const std::vector<glm::vec3> normals = sphere_directions(300);
    std::vector<double> exact(normals.size(), 0.0);
    for (std::size_t k = 0; k < normals.size(); ++k) {
        for (const glm::vec3& d : quadrature) {
            exact[k] +=
                static_cast<double>(radiance(d).y * std::max(0.0f, glm::dot(normals[k], d)));
        }
        exact[k] *= 4.0 * glm::pi<double>() / static_cast<double>(quadrature.size());
    }
    const double brightest = *std::max_element(exact.begin(), exact.end());
    BasisError out;
    double square = 0.0;
    for (std::size_t k = 0; k < normals.size(); ++k) {
        if (exact[k] < 0.03 * brightest) {
            continue;
        }
        const double relative =
            std::abs(static_cast<double>(probes.probe_irradiance(0, normals[k]).y) - exact[k]) /
            exact[k];
        out.worst = std::max(out.worst, relative);
        square += relative * relative;
        ++out.normals;
    }
    out.rms = out.normals > 0 ? std::sqrt(square / out.normals) : 0.0;
    return out;
}

TEST(IrradianceProbes, TheOctahedralMapHoldsTheDimSideThatHarmonicsMiss) {
    // A probe in a room with an open side: a lamp-lit patch, bright, in a cone around +x (35
    // degrees: a pool of light; 50: a lit wall), the floor below, dim, the rest black.
    // Irradiance for normals turned away from the patch falls to a few per cent of the bright
    // side's, and band-2 harmonics ring there (in the skinned-figure level, -40% on such
    // faces: docs/RESULTS.md). The octahedral map must hold both within 4% rms; the harmonics
    // are measured beside it, and must be the worse by half on the pool of light.
    for (const float degrees : {35.0f, 50.0f}) {
        const float edge = std::cos(glm::radians(degrees));
        const auto radiance = [edge](const glm::vec3& d) {
            if (d.x > edge) {
                return glm::vec3(10.0f, 8.0f, 6.0f);
            }
            return d.y < 0.0f ? glm::vec3(0.3f) : glm::vec3(0.0f);
        };
        const BasisError oct = basis_error(ProbeBasis::Octahedral, radiance);
        const BasisError sh = basis_error(ProbeBasis::Sh2, radiance);
        std::printf(
            "[ figures  ] a %.0f-degree patch: octahedral rms %.1f%% (worst %.1f%%), "
            "band-2 SH rms %.1f%% (worst %.1f%%), over %d normals\n",
            static_cast<double>(degrees), 100.0 * oct.rms, 100.0 * oct.worst, 100.0 * sh.rms,
            100.0 * sh.worst, oct.normals);
        ASSERT_GT(oct.normals, 200);
        EXPECT_LT(oct.rms, 0.04) << degrees;
        EXPECT_LT(oct.worst, 0.2) << degrees;
        if (degrees < 40.0f) {
            EXPECT_LT(oct.rms, 0.5 * sh.rms);
        }
    }
}

TEST(IrradianceProbes, GridCoversTheLevelWithProbesHalfASpacingOutside) {
    AxisBox level;
    level.add({0.0f, 0.0f, 0.0f});
    level.add({3.0f, 2.0f, 4.0f});
    const ProbeGrid grid = fit_probe_grid(level, 0.5f, 4096);
    EXPECT_EQ(grid.counts, glm::ivec3(8, 6, 10));
    EXPECT_FLOAT_EQ(grid.spacing, 0.5f);
    EXPECT_NEAR(grid.origin.x, -0.25f, 1e-5f);
    EXPECT_NEAR(grid.position(grid.counts - 1).z, 4.25f, 1e-5f);
    // Too many probes: the spacing grows until the grid fits.
    const ProbeGrid coarse = fit_probe_grid(level, 0.01f, 500);
    EXPECT_LE(coarse.size(), 500u);
    EXPECT_GT(coarse.size(), 100u);
    EXPECT_GT(coarse.spacing, 0.01f);
    // Nothing sensible to fit: no probes.
    EXPECT_EQ(fit_probe_grid(AxisBox{}, 0.5f, 4096).size(), 0u);
    AxisBox broken;
    broken.add({0.0f, std::nanf(""), 0.0f});
    EXPECT_EQ(fit_probe_grid(broken, 0.5f, 4096).size(), 0u);
    EXPECT_EQ(fit_probe_grid(level, 0.0f, 4096).size(), 0u);
    EXPECT_EQ(fit_probe_grid(level, 0.5f, 0).size(), 0u);
}

// --- Scenes -----------------------------------------------------------------------------

/// Appends the box [lo, hi] (luxel::testing::append_box) facing inwards (`inwards`: a room)
/// or outwards, all of surface `surface`, light-map UVs at the one-texel pages' centre.
void add_box(TriangleMesh& mesh, const glm::vec3& lo, const glm::vec3& hi, bool inwards,
             std::int32_t surface) {
    const std::size_t first = mesh.indices.size();
    luxel::testing::append_box(lo, hi, mesh.positions, mesh.indices);
    mesh.lightmap_uvs.resize(mesh.positions.size(), glm::vec2(0.5f));
    for (std::size_t i = first; inwards && i < mesh.indices.size(); i += 3) {
        std::swap(mesh.indices[i + 1], mesh.indices[i + 2]);
    }
    const std::size_t triangles = (mesh.indices.size() - first) / 3;
    mesh.surface_ids.insert(mesh.surface_ids.end(), triangles, surface);
    mesh.material_ids.insert(mesh.material_ids.end(), triangles, 0u);
}

/// An atlas of one-texel pages, surface s on page s, each of the given radiance.
RadianceAtlas flat_atlas(const std::vector<glm::vec3>& radiance) {
    RadianceAtlas atlas;
    for (std::size_t s = 0; s < radiance.size(); ++s) {
        atlas.pages.emplace_back(1);
        atlas.pages.back().at(0, 0) = radiance[s];
        atlas.surface_page.push_back(static_cast<std::int32_t>(s));
    }
    return atlas;
}

/// Probes over [lo, hi] gathered to convergence (every pass of every probe) in a scene of
/// static `meshes` and `dynamic` ones, lit by `atlas` through the CPU gather's rays.
struct ConvergedProbes {
    RayScene scene;
    RadianceAtlas atlas;
    JobSystem jobs{2};
    std::unique_ptr<CpuGatherer> gatherer;
    std::unique_ptr<IrradianceProbes> probes;

    ConvergedProbes(const std::vector<TriangleMesh>& meshes, RadianceAtlas lights,
                    const glm::vec3& lo, const glm::vec3& hi,
                    const std::vector<TriangleMesh>& dynamic = {})
        : atlas(std::move(lights)) {
        for (const TriangleMesh& mesh : meshes) {
            scene.add_object(mesh, glm::mat4(1.0f), false);
        }
        for (const TriangleMesh& mesh : dynamic) {
            scene.add_object(mesh, glm::mat4(1.0f), true);
        }
        scene.commit();
        gatherer = std::make_unique<CpuGatherer>(scene, atlas, CpuGatherSettings{64, 1e6f});
        AxisBox level;
        level.add(lo);
        level.add(hi);
        probes = std::make_unique<IrradianceProbes>(fit_probe_grid(level, 0.5f, 4096),
                                                    IrradianceProbeSettings{});
        const ProbeRayTracer tracer = [this](const glm::vec3& origin,
                                             std::span<const glm::vec3> directions,
                                             std::span<ProbeRay> rays, std::uint32_t seed) {
            gatherer->trace_probe_rays(origin, directions, rays, seed);
        };
        for (int guard = 0; guard < 10000 && probes->pending() > 0; ++guard) {
            probes->gather(64, tracer, &jobs);
        }
    }
};

TEST(IrradianceProbes, ClosedBoxOfConstantRadianceGivesPiLEverywhereInside) {
    TriangleMesh room;
    add_box(room, {0, 0, 0}, {3, 2.5f, 4}, true, 0);
    const glm::vec3 l(0.4f, 0.8f, 1.6f);
    const ConvergedProbes lit({room}, flat_atlas({l}), {0, 0, 0}, {3, 2.5f, 4});
    const IrradianceProbes& probes = *lit.probes;
    ASSERT_EQ(probes.pending(), 0u);
    // Probes half a spacing outside the walls see the room's backs: out.
    std::size_t active = 0;
    for (const ProbeState& p : probes.probes()) {
        active += p.active ? 1 : 0;
    }
    EXPECT_EQ(active, 6u * 5u * 8u);
    // Anywhere, facing anywhere, from the middle to a corner (0.2 m from three walls: the
    // visibility test looks from a quarter spacing off the surface, still inside).
    for (const glm::vec3& point :
         {glm::vec3(1.5f, 1.2f, 2.0f), glm::vec3(0.2f, 0.2f, 0.2f), glm::vec3(2.8f, 0.3f, 3.7f)}) {
        for (const glm::vec3& n : sphere_directions(12)) {
            const glm::vec3 e = probes.irradiance(point, n);
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(e[c], glm::pi<float>() * l[c], 0.01f * glm::pi<float>() * l[c])
                    << point.x << " " << point.y << " " << point.z << " n " << n.x << " " << n.y
                    << " " << n.z;
            }
        }
    }
    // Nothing non-finite is ever returned.
    EXPECT_EQ(probes.irradiance({std::nanf(""), 0, 0}, {0, 1, 0}), glm::vec3(0.0f));
    EXPECT_EQ(probes.irradiance({1, 1, 1}, {0, 0, 0}), glm::vec3(0.0f));
}

TEST(IrradianceProbes, TenCentimetreWallKeepsALitRoomsLightOutOfTheDarkOne) {
    // Two rooms side by side, x < -0.05 and x > 0.05, one wall 10 cm thick between: the left
    // room's surfaces glow, the right room's are black.
    TriangleMesh mesh;
    add_box(mesh, {-3, 0, 0}, {-0.05f, 2.5f, 3}, true, 0);  // left room, lit
    add_box(mesh, {0.05f, 0, 0}, {3, 2.5f, 3}, true, 1);    // right room, dark
    const ConvergedProbes rooms({mesh}, flat_atlas({glm::vec3(1.0f), glm::vec3(0.0f)}), {-3, 0, 0},
                                {3, 2.5f, 3});
    const IrradianceProbes& probes = *rooms.probes;
    ASSERT_EQ(probes.pending(), 0u);
    const float lit = glm::pi<float>();
    // Receivers 5 cm to 1 m from the wall, facing it, along it and away from it, each seen
    // from a camera in its own room.
    const glm::vec3 dark_camera(1.5f, 1.6f, 2.5f);
    const glm::vec3 lit_camera(-1.5f, 1.6f, 2.5f);
    for (const float distance : {0.05f, 0.1f, 0.3f, 1.0f}) {
        for (const glm::vec3& n :
             {glm::vec3(-1, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)}) {
            const glm::vec3 dark_point(0.05f + distance, 1.2f, 1.3f);
            EXPECT_LT(probes.irradiance(dark_point, n, dark_camera).x, 0.01f * lit)
                << "dark room, " << distance << " m from the wall, n.x " << n.x;
            const glm::vec3 lit_point(-0.05f - distance, 1.2f, 1.3f);
            EXPECT_NEAR(probes.irradiance(lit_point, n, lit_camera).x, lit, 0.02f * lit)
                << "lit room, " << distance << " m from the wall, n.x " << n.x;
        }
    }
}

TEST(IrradianceProbes, RaysPassThroughGeometryWithoutALightMap) {
    // A closed glowing room with a dark crate (surface 1, no light map) in it: the crate must
    // not darken the probes that light it, nor their neighbours.
    TriangleMesh room;
    add_box(room, {0, 0, 0}, {3, 2.5f, 3}, true, 0);
    TriangleMesh crate;
    add_box(crate, {1.1f, 0.0f, 1.1f}, {1.9f, 0.8f, 1.9f}, false, 1);
    RadianceAtlas atlas = flat_atlas({glm::vec3(1.0f)});
    atlas.surface_page.push_back(-1);  // the crate: no light map
    const ConvergedProbes lit({room}, std::move(atlas), {0, 0, 0}, {3, 2.5f, 3}, {crate});
    const IrradianceProbes& probes = *lit.probes;
    ASSERT_EQ(probes.pending(), 0u);
    // On the crate's top and sides, as everywhere in the room: pi.
    EXPECT_NEAR(probes.irradiance({1.5f, 0.8f, 1.5f}, {0, 1, 0}).x, glm::pi<float>(), 0.03f);
    EXPECT_NEAR(probes.irradiance({1.9f, 0.4f, 1.5f}, {1, 0, 0}).x, glm::pi<float>(), 0.03f);
    for (std::size_t i = 0; i < probes.probes().size(); ++i) {
        if (probes.probes()[i].active) {
            EXPECT_NEAR(probes.probe_irradiance(i, {0, 1, 0}).x, glm::pi<float>(), 0.03f);
        }
    }
}

TEST(IrradianceProbes, AProbeInsideGeometryMovesOutOrStaysOut) {
    // A solid block around the grid point at (1.25, 1.25, 1.25) (0.5 m spacing over [0, 3]^3
    // puts probes at -0.25 + 0.5 k): 10 cm thick, it is left by moving 5+ cm; 90 cm thick,
    // the probe stays out.
    for (const float half : {0.05f, 0.45f}) {
        TriangleMesh mesh;
        add_box(mesh, {0, 0, 0}, {3, 3, 3}, true, 0);
        add_box(mesh, glm::vec3(1.25f - half, 0.5f, 1.25f - half),
                glm::vec3(1.25f + half, 2.0f, 1.25f + half), false, 0);
        const ConvergedProbes lit({mesh}, flat_atlas({glm::vec3(1.0f)}), {0, 0, 0}, {3, 3, 3});
        const IrradianceProbes& probes = *lit.probes;
        ASSERT_EQ(probes.grid().counts, glm::ivec3(8));
        ASSERT_EQ(probes.pending(), 0u);
        const ProbeState& inside = probes.probes()[probes.grid().index({3, 3, 3})];
        if (half < 0.1f) {
            EXPECT_TRUE(inside.active);
            EXPECT_GT(glm::length(inside.offset), half);
            EXPECT_LT(glm::length(inside.offset), 0.45f * 0.5f + 1e-4f);
        } else {
            EXPECT_FALSE(inside.active);
        }
        // Points beside the pillar are still lit from the probes around them.
        EXPECT_NEAR(probes.irradiance({1.25f + half + 0.05f, 1.3f, 1.25f}, {1, 0, 0}).x,
                    glm::pi<float>(), 0.03f * glm::pi<float>());
    }
}

}  // namespace
