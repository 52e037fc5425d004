#include "luxel/lighting/gpu/hemi_plane_gatherer.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include <glm/gtc/constants.hpp>

#include "gather/gather_interface.h"
#include "gather_geometry.hpp"
#include "luxel/lighting/core/cpu_gather.hpp"
#include "luxel/lighting/core/splitmix.hpp"
#include "luxel/lighting/gpu/hemi_plane_geometry.hpp"
#include "luxel/lighting/gpu/sky_texture.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/runtime/gl_limits.hpp"
#include "luxel/runtime/gl_state_guard.hpp"
#include "luxel/runtime/program.hpp"
#include "luxel/runtime/shader_library.hpp"
#include "radiance_texture.hpp"

namespace luxel::lighting {
namespace {

/// std430 GatherView of shaders/gather/gather_interface.h, which the shaders include too.
struct GpuView {
    glm::vec4 origin;
    glm::vec4 right;
    glm::vec4 up;
    glm::vec4 forward;
};
static_assert(sizeof(GpuView) == GATHER_VIEW_SIZE);
static_assert(offsetof(GpuView, origin) == GATHER_VIEW_ORIGIN);
static_assert(offsetof(GpuView, right) == GATHER_VIEW_RIGHT);
static_assert(offsetof(GpuView, up) == GATHER_VIEW_UP);
static_assert(offsetof(GpuView, forward) == GATHER_VIEW_FORWARD);

// Shader binding points (gather_interface.h).
constexpr GLuint kViewsBinding = GATHER_VIEWS_BINDING;
constexpr GLuint kSurfacePagesBinding = GATHER_SURFACE_PAGES_BINDING;
constexpr GLuint kWeightsBinding = GATHER_WEIGHTS_BINDING;
constexpr GLuint kSumsBinding = GATHER_SUMS_BINDING;
constexpr GLuint kRadianceUnit = GATHER_RADIANCE_UNIT;
constexpr GLuint kTilesUnit = GATHER_TILES_UNIT;
constexpr GLuint kSkyUnit = GATHER_SKY_UNIT;

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// The view of one texel, or nullopt-like `valid = false` for a texel without a usable normal
/// or position (its irradiance is zero, as CpuGatherer's).
struct TexelView {
    GpuView view{};
    bool valid = false;
    /// Three numbers in [0, 1) for this texel and pass: the plane's turn about the normal and
    /// the shift of the horizon rays' sequence.
    glm::vec3 random{0.0f};
};

/// Three numbers from the texel centre's bits and the pass: unrelated for neighbouring texels
/// and consecutive passes, the same on every run.
glm::vec3 texel_numbers(const glm::vec3& position, std::uint32_t pass) {
    std::uint64_t h = pass;
    glm::vec3 out(0.0f);
    for (int i = 0; i < 3; ++i) {
        std::uint32_t bits = 0;
        std::memcpy(&bits, &position[i], sizeof(bits));
        h ^= static_cast<std::uint64_t>(bits) << (i == 1 ? 32 : 0);
        out[i] = unit_interval(splitmix64(h));
    }
    return out;
}

TexelView make_view(const GatherTexel& texel, bool rotate) {
    TexelView result;
    const float length = glm::length(texel.normal);
    if (!finite(texel.position) || !(length > 0.0f) || !std::isfinite(length)) {
        result.view = {glm::vec4(0.0f), {1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};
        return result;
    }
    HemiPlaneFrame frame = hemi_plane_frame(texel.normal / length);
    result.random = texel_numbers(texel.position, texel.pass);
    if (rotate) {
        // The plane turned about the normal: the square's corners, its pixel grid and the band
        // it misses fall elsewhere each pass (right x up stays -forward).
        const float angle = glm::two_pi<float>() * result.random.x;
        const glm::vec3 right = std::cos(angle) * frame.right + std::sin(angle) * frame.up;
        frame.up = -std::sin(angle) * frame.right + std::cos(angle) * frame.up;
        frame.right = right;
    }
    // The CPU backend starts its rays from the same offset point; starting both there keeps
    // the two backends' answers comparable texel for texel.
    const glm::vec3 origin = offset_ray_origin(texel.position, frame.forward);
    result.view = {glm::vec4(origin, 1.0f), glm::vec4(frame.right, 0.0f), glm::vec4(frame.up, 0.0f),
                   glm::vec4(frame.forward, 0.0f)};
    result.valid = true;
    return result;
}

void validate(const HemiPlaneSettings& s) {
    if (s.resolution < 1 || s.resolution > 4096) {
        throw Error("HemiPlaneSettings.resolution must be in [1, 4096], got " +
                    std::to_string(s.resolution));
    }
    if (!(s.half_width > 0.0f) || !std::isfinite(s.half_width)) {
        throw Error("HemiPlaneSettings.half_width must be positive and finite");
    }
    if (s.texels_per_batch < 1) {
        throw Error("HemiPlaneSettings.texels_per_batch must be at least 1, got " +
                    std::to_string(s.texels_per_batch));
    }
    if (!(s.near_fraction > 0.0f) || !(s.near_fraction < 1.0f)) {
        throw Error("HemiPlaneSettings.near_fraction must be in (0, 1)");
    }
    if (s.horizon_rays < 0 || s.horizon_rays > 65536) {
        throw Error("HemiPlaneSettings.horizon_rays must be in [0, 65536], got " +
                    std::to_string(s.horizon_rays));
    }
    if (s.specular_rays < 0 || s.specular_rays > 65536) {
        throw Error("HemiPlaneSettings.specular_rays must be in [0, 65536], got " +
                    std::to_string(s.specular_rays));
    }
}

/// Up to `count` directions cosine-distributed over the part of the hemisphere about `view`'s
/// forward axis that its plane of half-width `a` does not show (|x| > a z or |y| > a z in the
/// view's frame; `inside`: the part it shows): points of the R2 sequence shifted by `shift`,
/// mapped to the cosine-weighted hemisphere, kept when they fall in the part. A low-discrepancy
/// sequence restricted to a region stays evenly spread over it; 1 - F(a) of the points land
/// outside the plane (16.9% at a = 2).
void band_directions(const GpuView& view, float a, int count, glm::vec2 shift, bool inside,
                     std::vector<glm::vec3>& out) {
    out.clear();
    const glm::vec3 right(view.right);
    const glm::vec3 up(view.up);
    const glm::vec3 forward(view.forward);
    const int attempts = count * 64;
    for (int i = 0; i < attempts && static_cast<int>(out.size()) < count; ++i) {
        glm::vec2 u = shift + static_cast<float>(i) * glm::vec2(0.7548776662f, 0.5698402910f);
        u -= glm::floor(u);
        const float r = std::sqrt(u.x);
        const float phi = glm::two_pi<float>() * u.y;
        const float x = r * std::cos(phi);
        const float y = r * std::sin(phi);
        const float z = std::sqrt(std::max(0.0f, 1.0f - u.x));
        const bool outside = std::abs(x) > a * z || std::abs(y) > a * z;
        if (outside != inside) {
            out.push_back(glm::normalize(x * right + y * up + z * forward));
        }
    }
}

int tiles_across(int batch) {
    return static_cast<int>(std::ceil(std::sqrt(static_cast<double>(batch))));
}

/// The largest batch whose atlas fits the driver's framebuffer and texture limits.
int fit_batch(int batch, int resolution) {
    const int limit = gl::largest_render_target();
    const int max_tiles = std::max(limit / resolution, 1);
    return std::min(batch, max_tiles * max_tiles);
}

}  // namespace

struct HemiPlaneGatherer::Impl {
    const RayScene* scene;
    const RadianceAtlas* atlas;
    HemiPlaneSettings settings;
    HemiPlaneStats stats;
    double coverage = 0.0;
    int tiles_x = 1;
    int tiles_y = 1;

    gl::Program scene_program;
    gl::Program reduce_program;
    GatherGeometry geometry;
    RadianceTexture radiance;
    SkyTexture sky;  ///< what the pixels that leave the level read
    gl::Texture tiles;
    gl::Renderbuffer depth;
    gl::Framebuffer framebuffer;
    gl::Buffer weights;
    gl::Buffer views;
    gl::Buffer sums;
    /// The band the plane misses and the light behind mirrors and glass, traced on the CPU as
    /// the CPU gather traces its rays.
    CpuGatherer horizon;
    const std::vector<TraceMaterial>* materials = nullptr;
    bool materials_changed = false;

    Impl(const RayScene& s, const RadianceAtlas& a, HemiPlaneSettings settings_in,
         const ShaderLibrary& shaders)
        : scene(&s), atlas(&a), settings(settings_in), horizon(s, a) {
        validate(settings);
        settings.texels_per_batch = fit_batch(settings.texels_per_batch, settings.resolution);
        coverage = hemi_plane_coverage(static_cast<double>(settings.half_width));
        scene_program = shaders.build({{ShaderStage::Vertex, "gather/hemi_plane.vert"},
                                       {ShaderStage::Fragment, "gather/hemi_plane.frag"}});
        reduce_program = shaders.build({{ShaderStage::Compute, "gather/hemi_plane_reduce.comp"}});

        tiles_x = tiles_across(settings.texels_per_batch);
        tiles_y = (settings.texels_per_batch + tiles_x - 1) / tiles_x;
        const int width = tiles_x * settings.resolution;
        const int height = tiles_y * settings.resolution;
        // 32-bit float radiance: the source's 8-bit mip-chain sum is its known weakness.
        tiles = gl::Texture::create_2d(GL_RGBA32F, width, height);
        glTextureParameteri(tiles.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(tiles.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        // Float depth for the reversed-depth projection (depth = near / z).
        depth = gl::Renderbuffer::create(GL_DEPTH_COMPONENT32F, width, height);
        framebuffer = gl::Framebuffer::create();
        framebuffer.attach(GL_COLOR_ATTACHMENT0, tiles);
        framebuffer.attach(GL_DEPTH_ATTACHMENT, depth);
        framebuffer.check_complete("HemiPlaneGatherer tile atlas");

        const std::vector<float> w =
            hemi_plane_weights(settings.resolution, static_cast<double>(settings.half_width));
        weights = gl::Buffer::create(w.size() * sizeof(float), w.data(), 0);

        const int grid[2] = {tiles_x, tiles_y};
        glProgramUniform2iv(scene_program.id(), scene_program.uniform_location("u_tile_grid"), 1,
                            grid);
        scene_program.set("u_half_width", settings.half_width);
        reduce_program.set("u_tiles_x", tiles_x);
        reduce_program.set("u_resolution", settings.resolution);
        reduce_program.set("u_half_width", settings.half_width);
        gl::check_error("HemiPlaneGatherer setup");
    }

    /// Grows the per-call buffers to hold `count` texels.
    void reserve(std::size_t count) {
        if (views.size() < count * sizeof(GpuView)) {
            views = gl::Buffer::create(count * sizeof(GpuView));
        }
        if (sums.size() < count * sizeof(glm::vec4)) {
            sums = gl::Buffer::create(count * sizeof(glm::vec4), nullptr, 0);
        }
    }

    [[nodiscard]] float near_plane() const {
        const glm::vec3 lo = scene->bounds_min();
        const glm::vec3 hi = scene->bounds_max();
        const float diagonal = glm::all(glm::lessThanEqual(lo, hi)) ? glm::length(hi - lo) : 0.0f;
        const float near = settings.near_fraction * diagonal;
        return near > 0.0f && std::isfinite(near) ? near : settings.near_fraction;
    }

    void render_batch(int first, int count) {
        const float clear_colour[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        const float clear_depth = 0.0f;  // reversed depth: 0 is infinitely far
        glClearNamedFramebufferfv(framebuffer.id(), GL_COLOR, 0, clear_colour);
        glClearNamedFramebufferfv(framebuffer.id(), GL_DEPTH, 0, &clear_depth);
        scene_program.use();
        scene_program.set("u_first_view", first);
        for (const auto& [id, object] : geometry.objects()) {
            if (object.index_count == 0) {
                continue;
            }
            const glm::mat4 model = scene->transform(id);
            scene_program.set("u_model", model);
            scene_program.set("u_mirrored", glm::determinant(glm::mat3(model)) < 0.0f ? 1 : 0);
            glBindVertexArray(object.vertex_array.id());
            glDrawElementsInstanced(GL_TRIANGLES, object.index_count, GL_UNSIGNED_INT, nullptr,
                                    count);
            ++stats.draws;
        }
        reduce_program.use();
        reduce_program.set("u_first_view", first);
        glBindTextureUnit(kTilesUnit, tiles.id());
        glDispatchCompute(static_cast<GLuint>(count), 1, 1);
        glBindTextureUnit(kTilesUnit, 0);
        ++stats.batches;
    }

    /// Per texel, the band's irradiance pi (1 - F(a)) mean(L) from settings.horizon_rays rays;
    /// empty without horizon rays. A texel whose band rays could not be placed (none fell
    /// outside the plane: never at a = 2) gets the plane's assumption instead.
    std::vector<std::optional<glm::vec3>> trace_horizon(const std::vector<GpuView>& gpu_views,
                                                        const std::vector<bool>& valid,
                                                        const std::vector<glm::vec2>& shifts) {
        if (settings.horizon_rays <= 0) {
            return {};
        }
        std::vector<std::optional<glm::vec3>> band(gpu_views.size());
        std::vector<glm::vec3> directions;
        std::vector<glm::vec3> band_radiance;
        const float share = static_cast<float>(glm::pi<double>() * (1.0 - coverage));
        for (std::size_t i = 0; i < gpu_views.size(); ++i) {
            if (!valid[i]) {
                continue;
            }
            band_directions(gpu_views[i], settings.half_width, settings.horizon_rays, shifts[i],
                            false, directions);
            if (directions.empty()) {
                continue;
            }
            band_radiance.resize(directions.size());
            const auto seed = static_cast<std::uint32_t>(shifts[i].x * 4294967040.0f);
            horizon.trace_gather_rays(glm::vec3(gpu_views[i].origin), directions, band_radiance,
                                      seed);
            glm::dvec3 sum(0.0);
            for (const glm::vec3& l : band_radiance) {
                sum += glm::dvec3(l);
            }
            band[i] = glm::vec3(sum / static_cast<double>(band_radiance.size())) * share;
            stats.horizon_rays += band_radiance.size();
        }
        return band;
    }

    /// Per texel whose plane showed a mirror or glass (the reduction's alpha), the light behind
    /// it: pi F(a) times the mean over settings.specular_rays rays cosine-distributed over the
    /// plane's view of what those whose first hit is specular bring back. Empty when no texel
    /// needs it or without a material table.
    std::vector<glm::vec3> trace_specular(const std::vector<GpuView>& gpu_views,
                                          const std::vector<bool>& valid,
                                          const std::vector<glm::vec2>& shifts,
                                          const std::vector<glm::vec4>& plane) {
        if (settings.specular_rays <= 0 || materials == nullptr) {
            return {};
        }
        std::vector<glm::vec3> out;
        std::vector<glm::vec3> directions;
        std::vector<glm::vec3> light;
        std::vector<std::uint8_t> through;
        const float share = static_cast<float>(glm::pi<double>() * coverage);
        for (std::size_t i = 0; i < gpu_views.size(); ++i) {
            if (!valid[i] || !(plane[i].w > 0.0f)) {
                continue;
            }
            // Another stretch of the sequence than the horizon rays'.
            const glm::vec2 shift = glm::fract(shifts[i] + glm::vec2(0.5f));
            band_directions(gpu_views[i], settings.half_width, settings.specular_rays, shift, true,
                            directions);
            if (directions.empty()) {
                continue;
            }
            light.resize(directions.size());
            through.assign(directions.size(), 0);
            const auto seed = static_cast<std::uint32_t>(shift.x * 4294967040.0f);
            horizon.trace_gather_rays(glm::vec3(gpu_views[i].origin), directions, light, seed,
                                      through);
            glm::dvec3 sum(0.0);
            for (std::size_t k = 0; k < light.size(); ++k) {
                if (through[k] != 0) {
                    sum += glm::dvec3(light[k]);
                }
            }
            out.resize(gpu_views.size(), glm::vec3(0.0f));
            out[i] = glm::vec3(sum / static_cast<double>(light.size())) * share;
            stats.specular_rays += light.size();
        }
        return out;
    }

    void gather(std::span<const GatherTexel> texels, std::span<glm::vec3> irradiance) {
        const std::size_t count = std::min(texels.size(), irradiance.size());
        if (count == 0) {
            return;
        }
        std::vector<GpuView> gpu_views(count);
        std::vector<bool> valid(count);
        std::vector<glm::vec2> shifts(count);
        for (std::size_t i = 0; i < count; ++i) {
            const TexelView v = make_view(texels[i], settings.rotate);
            gpu_views[i] = v.view;
            valid[i] = v.valid;
            shifts[i] = glm::vec2(v.random.y, v.random.z);
        }

        const gl::StateGuard guard;
        if (materials_changed) {
            geometry.clear();
            materials_changed = false;
        }
        geometry.sync(*scene, materials);
        const std::uint64_t pages_before = radiance.page_uploads();
        radiance.sync(*atlas);
        // A pixel where nothing was drawn looks out of the level: the reduction reads the sky
        // there, as the CPU gather's escaping rays do (docs/METHOD.md §6.11).
        const bool sky_on = sky.sync(*atlas);
        reduce_program.set("u_sky_on", sky_on ? 1 : 0);
        stats.page_uploads += radiance.page_uploads() - pages_before;
        stats.object_uploads = geometry.uploads();
        reserve(count);
        views.update(0, count * sizeof(GpuView), gpu_views.data());
        scene_program.set("u_near", near_plane());

        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer.id());
        glViewport(0, 0, tiles_x * settings.resolution, tiles_y * settings.resolution);
        glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_GREATER);
        glDepthMask(GL_TRUE);
        // Both sides are drawn: a back face must still hide what lies behind it.
        glDisable(GL_CULL_FACE);
        glDisable(GL_BLEND);
        glDisable(GL_SCISSOR_TEST);
        for (GLenum i = 0; i < 4; ++i) {
            glEnable(GL_CLIP_DISTANCE0 + i);
        }
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kViewsBinding, views.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kSurfacePagesBinding, radiance.surface_table());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kWeightsBinding, weights.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kSumsBinding, sums.id());
        glBindTextureUnit(kRadianceUnit, radiance.texture());
        if (sky_on) {
            glBindTextureUnit(kSkyUnit, sky.id());
        }

        const auto batch = static_cast<std::size_t>(settings.texels_per_batch);
        for (std::size_t first = 0; first < count; first += batch) {
            render_batch(static_cast<int>(first), static_cast<int>(std::min(batch, count - first)));
        }

        // While the GPU draws: the band the plane misses, on the CPU.
        const std::vector<std::optional<glm::vec3>> band = trace_horizon(gpu_views, valid, shifts);

        // The reduction wrote the sums through an SSBO: make them visible to the read-back.
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        std::vector<glm::vec4> result(count);
        glGetNamedBufferSubData(sums.id(), 0, static_cast<GLsizeiptr>(count * sizeof(glm::vec4)),
                                result.data());
        glBindTextureUnit(kRadianceUnit, 0);
        glBindTextureUnit(kSkyUnit, 0);
        gl::check_error("HemiPlaneGatherer::gather");

        const std::vector<glm::vec3> specular = trace_specular(gpu_views, valid, shifts, result);
        const float pi = glm::pi<float>();
        const float assumed = static_cast<float>(glm::pi<double>() / coverage);
        for (std::size_t i = 0; i < count; ++i) {
            // With the band traced, the plane's sum is its own share of the hemisphere; without,
            // it stands for the whole.
            glm::vec3 e = band.empty() || !band[i] ? glm::vec3(result[i]) * assumed
                                                   : glm::vec3(result[i]) * pi + *band[i];
            if (!specular.empty()) {
                e += specular[i];
            }
            for (int c = 0; c < 3; ++c) {
                // The contract: never NaN or negative, whatever the atlas held.
                e[c] = e[c] >= 0.0f && std::isfinite(e[c]) ? e[c] : 0.0f;
            }
            irradiance[i] = valid[i] ? e : glm::vec3(0.0f);
        }
        stats.texels += count;
    }
};

HemiPlaneGatherer::HemiPlaneGatherer(const RayScene& scene, const RadianceAtlas& atlas,
                                     HemiPlaneSettings settings)
    : HemiPlaneGatherer(scene, atlas, settings, ShaderLibrary{}) {}

HemiPlaneGatherer::HemiPlaneGatherer(const RayScene& scene, const RadianceAtlas& atlas,
                                     HemiPlaneSettings settings, const ShaderLibrary& shaders)
    : impl_(std::make_unique<Impl>(scene, atlas, settings, shaders)) {}

HemiPlaneGatherer::~HemiPlaneGatherer() = default;

void HemiPlaneGatherer::gather(std::span<const GatherTexel> texels,
                               std::span<glm::vec3> irradiance) {
    impl_->gather(texels, irradiance);
}

void HemiPlaneGatherer::set_materials(const std::vector<TraceMaterial>* materials) {
    if (materials != impl_->materials) {
        impl_->materials = materials;
        impl_->horizon.set_materials(materials);
        // Specular triangles are marked at upload: the next gather (in its GL context)
        // uploads every object again.
        impl_->materials_changed = true;
    }
}

bool HemiPlaneGatherer::refines() const {
    return impl_->settings.rotate || impl_->settings.horizon_rays > 0;
}

void HemiPlaneGatherer::refresh_geometry() {
    impl_->geometry.clear();
}

const HemiPlaneSettings& HemiPlaneGatherer::settings() const {
    return impl_->settings;
}

const HemiPlaneStats& HemiPlaneGatherer::stats() const {
    return impl_->stats;
}

}  // namespace luxel::lighting
