// The caustic layer of the light maps (issue 23): the views that the camera's screen-space
// caustics cannot serve (a specular cube map's faces: the pool floor seen through its water)
// read caustic irradiance per light-map texel. The layer is built on the GPU from the caustic
// pass's photons; here it is checked texel for texel against the same binning done on the CPU
// from the lighting system's photon lists, for its energy, for redrawing only when the photons
// change, and in the frame: the water's reflection and refraction show the pool's caustics.

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "luxel/lighting/gpu/caustic_light_maps.hpp"
#include "luxel/lighting/gpu/caustic_pass.hpp"
#include "luxel/renderer/frame_renderer.hpp"
#include "luxel/runtime/shader_library.hpp"
#include "render_scenes.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;

/// The caustics level, lit until its caustic lists hold photons.
struct CausticsLevel {
    std::unique_ptr<GlContext> context = test::make_render_context();
    test::RenderWorld world;

    CausticsLevel() {
        world.load_level("caustics");
        world.start();
        for (int i = 0; i < 6; ++i) {
            world.update(1e9);
        }
    }
};

/// Every layer of a 2D array texture, RGBA floats.
std::vector<glm::vec4> read_layers(const CausticLightMaps& maps) {
    const std::size_t size = static_cast<std::size_t>(maps.layer_size());
    std::vector<glm::vec4> texels(size * size * static_cast<std::size_t>(maps.layers()));
    glFinish();
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(maps.texture(), 0, GL_RGBA, GL_FLOAT,
                      static_cast<GLsizei>(texels.size() * sizeof(glm::vec4)), texels.data());
    gl::check_error("read_layers");
    return texels;
}

/// The layer as the CPU bins it: each photon on a paged surface adds power / texel area to the
/// texel its light-map UV falls in (rgb) and 1 to the count (a).
std::vector<glm::dvec4> bin_on_cpu(const LightingSystem& lighting, int layer_size, int layers,
                                   double& binned_power) {
    const IlluminationMaps& maps = lighting.maps();
    std::vector<glm::dvec4> expected(static_cast<std::size_t>(layer_size) * layer_size * layers,
                                     glm::dvec4(0.0));
    binned_power = 0.0;
    for (const CausticPair& pair : lighting.photons().caustics()) {
        for (std::uint32_t k = 0; k < pair.photons.slice_count(); ++k) {
            for (const CausticPhoton& photon : pair.photons.slice(k)) {
                if (photon.surface < 0) {
                    continue;
                }
                const auto s = static_cast<std::size_t>(photon.surface);
                const std::int32_t page = maps.aim().surface_page.at(s);
                if (page < 0) {
                    continue;
                }
                const int size = maps.iim_pages()[static_cast<std::size_t>(page)].current.size;
                const glm::vec2 uv = photon.lightmap_uv();
                const int x = std::min(static_cast<int>(std::floor(uv.x * size)), size - 1);
                const int y = std::min(static_cast<int>(std::floor(uv.y * size)), size - 1);
                const double metres = maps.surfaces()[s].world_metres_per_texel;
                const std::size_t at =
                    (static_cast<std::size_t>(page) * layer_size + static_cast<std::size_t>(y)) *
                        layer_size +
                    static_cast<std::size_t>(x);
                expected[at] += glm::dvec4(glm::dvec3(photon.power) / (metres * metres), 1.0);
                binned_power += static_cast<double>(photon.power.r);
            }
        }
    }
    return expected;
}

TEST(CausticLightMaps, BinEveryPhotonIntoItsTexelWithItsPowerOverTheTexelArea) {
    CausticsLevel level;
    const LightingSystem& lighting = *level.world.lighting;
    ASSERT_FALSE(lighting.photons().caustics().empty());
    const ShaderLibrary shaders;
    CausticPass pass(CausticPassSettings{}, {16, 16}, shaders);
    pass.upload(lighting.photons().caustics());
    CausticLightMaps maps(shaders);
    EXPECT_TRUE(maps.sync(pass, lighting.maps()));
    ASSERT_FALSE(maps.empty());
    ASSERT_EQ(maps.layers(), static_cast<int>(lighting.maps().iim_pages().size()));

    double binned_power = 0.0;
    const std::vector<glm::dvec4> expected =
        bin_on_cpu(lighting, maps.layer_size(), maps.layers(), binned_power);
    const std::vector<glm::vec4> layer = read_layers(maps);
    ASSERT_EQ(layer.size(), expected.size());
    double brightest = 0.0;
    double photons = 0.0;
    for (const glm::dvec4& e : expected) {
        brightest = std::max(brightest, e.r);
        photons += e.a;
    }
    ASSERT_GT(photons, 1000.0) << "the level's caustics land on light-mapped surfaces";
    std::size_t wrong = 0;
    for (std::size_t i = 0; i < layer.size(); ++i) {
        const glm::dvec4 got(layer[i]);
        // Counts add exactly in float; irradiance to float rounding of the sums.
        const bool same = got.a == expected[i].a && std::abs(got.r - expected[i].r) <=
                                                        1e-5 * brightest + 1e-6 * expected[i].r;
        wrong += same ? 0 : 1;
        if (!same && wrong <= 5) {
            ADD_FAILURE() << "texel " << i << ": " << got.r << " (" << got.a << " photons), CPU "
                          << expected[i].r << " (" << expected[i].a << ")";
        }
    }
    EXPECT_EQ(wrong, 0u);
    EXPECT_GT(binned_power, 0.0);
}

TEST(CausticLightMaps, RedrawOnlyWhenThePhotonsChange) {
    CausticsLevel level;
    const ShaderLibrary shaders;
    CausticPass pass(CausticPassSettings{}, {16, 16}, shaders);
    CausticLightMaps maps(shaders);
    const auto sync = [&] {
        pass.upload(level.world.lighting->photons().caustics());
        return maps.sync(pass, level.world.lighting->maps());
    };
    EXPECT_TRUE(sync());
    EXPECT_FALSE(sync()) << "nothing changed";
    EXPECT_FALSE(sync());
    EXPECT_EQ(maps.redraws(), 1u);
    // The lighting keeps refining the still caustics: new slices, a redraw.
    bool redrawn = false;
    for (int i = 0; i < 8 && !redrawn; ++i) {
        level.world.update(1e9);
        redrawn = sync();
    }
    EXPECT_TRUE(redrawn);
    EXPECT_EQ(maps.redraws(), 2u);
    EXPECT_FALSE(sync());
}

/// Mean specular radiance over the pixels of specular materials, from the level's camera.
glm::dvec3 specular_mean(CausticsLevel& level, bool caustics) {
    renderer::FrameSettings settings;
    settings.width = 160;
    settings.height = 90;
    settings.specular_cube_size = 32;
    renderer::FrameRenderer renderer(level.world.registry, *level.world.lighting, settings);
    renderer.set_terms({.caustics = caustics});
    const renderer::FrameCamera camera = test::level_camera(level.world.registry, 160.0f / 90.0f);
    renderer.render(camera, level.world.time);
    const Image specular = renderer.read(renderer::FrameImage::Specular);
    const Image albedo = renderer.read(renderer::FrameImage::Albedo);
    glm::dvec3 sum(0.0);
    int pixels = 0;
    for (int y = 0; y < specular.height; ++y) {
        for (int x = 0; x < specular.width; ++x) {
            if (albedo.pixel(x, y).a < 0.5f) {
                continue;
            }
            sum += glm::dvec3(specular.pixel(x, y));
            ++pixels;
        }
    }
    EXPECT_GT(pixels, 100) << "the camera sees the water and the glass";
    return pixels > 0 ? sum / static_cast<double>(pixels) : sum;
}

TEST(CausticLightMaps, TheWaterShowsThePoolFloorsCaustics) {
    // The sun's light on the pool floor arrives only through the water (the water shadows the
    // direct sun): without the caustic layer the water's cube map sees that floor unlit.
    CausticsLevel level;
    const glm::dvec3 without = specular_mean(level, false);
    const glm::dvec3 with = specular_mean(level, true);
    EXPECT_GT(with.g, 2.0 * without.g) << without.g << " -> " << with.g;
    EXPECT_TRUE(std::isfinite(with.r) && std::isfinite(with.g) && std::isfinite(with.b));
}

/// The mean caustic radiance over the frame (frame with caustics minus without), with the
/// camera's caustics from the screen-space splat or from the caustic layer.
double caustic_mean(CausticsLevel& level, bool layer_in_view) {
    renderer::FrameSettings settings;
    settings.width = 160;
    settings.height = 90;
    settings.specular_cube_size = 32;
    settings.caustic_layer_in_view = layer_in_view;
    const renderer::FrameCamera camera = test::level_camera(level.world.registry, 160.0f / 90.0f);
    const auto mean_green = [&](bool caustics) {
        renderer::FrameRenderer renderer(level.world.registry, *level.world.lighting, settings);
        renderer.set_terms({.caustics = caustics, .specular = false});
        renderer.render(camera, level.world.time);
        const Image frame = renderer.read(renderer::FrameImage::Frame);
        double sum = 0.0;
        for (int y = 0; y < frame.height; ++y) {
            for (int x = 0; x < frame.width; ++x) {
                sum += static_cast<double>(frame.pixel(x, y).g);
            }
        }
        return sum / (static_cast<double>(frame.width) * frame.height);
    };
    return mean_green(true) - mean_green(false);
}

TEST(CausticLightMaps, TheCamerasCausticsFromTheLayerMatchTheSplatsInTheMean) {
    // Two estimators of the same photons' irradiance: binned per light-map texel, or splatted
    // per pixel and filtered. Over the frame they must agree (both keep the photons' power);
    // pixel for pixel they differ by their noise and blur.
    CausticsLevel level;
    const double splat = caustic_mean(level, false);
    const double layer = caustic_mean(level, true);
    ASSERT_GT(splat, 1e-3) << "the level's caustics are in view";
    EXPECT_NEAR(layer / splat, 1.0, 0.1) << splat << " vs " << layer;
}

}  // namespace
