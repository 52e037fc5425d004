#include "luxel/lighting/gpu/hemi_plane_gatherer.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include <glm/gtc/constants.hpp>

#include "gather/gather_interface.h"
#include "gather_geometry.hpp"
#include "luxel/lighting/gpu/hemi_plane_geometry.hpp"
#include "luxel/lighting/gpu/sky_texture.hpp"
#include "luxel/runtime/error.hpp"
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
};

TexelView make_view(const GatherTexel& texel) {
    TexelView result;
    const float length = glm::length(texel.normal);
    if (!finite(texel.position) || !(length > 0.0f) || !std::isfinite(length)) {
        result.view = {glm::vec4(0.0f), {1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};
        return result;
    }
    const HemiPlaneFrame frame = hemi_plane_frame(texel.normal / length);
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
}

int tiles_across(int batch) {
    return static_cast<int>(std::ceil(std::sqrt(static_cast<double>(batch))));
}

/// The largest batch whose atlas fits the driver's framebuffer and texture limits.
int fit_batch(int batch, int resolution) {
    GLint max_texture = 0;
    GLint max_width = 0;
    GLint max_height = 0;
    GLint max_renderbuffer = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_texture);
    glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &max_width);
    glGetIntegerv(GL_MAX_FRAMEBUFFER_HEIGHT, &max_height);
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_renderbuffer);
    const int limit = std::min({max_texture, max_width, max_height, max_renderbuffer});
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

    Impl(const RayScene& s, const RadianceAtlas& a, HemiPlaneSettings settings_in,
         const ShaderLibrary& shaders)
        : scene(&s), atlas(&a), settings(settings_in) {
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

    void gather(std::span<const GatherTexel> texels, std::span<glm::vec3> irradiance) {
        const std::size_t count = std::min(texels.size(), irradiance.size());
        if (count == 0) {
            return;
        }
        std::vector<GpuView> gpu_views(count);
        std::vector<bool> valid(count);
        for (std::size_t i = 0; i < count; ++i) {
            const TexelView v = make_view(texels[i]);
            gpu_views[i] = v.view;
            valid[i] = v.valid;
        }

        const gl::StateGuard guard;
        geometry.sync(*scene);
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

        // The reduction wrote the sums through an SSBO: make them visible to the read-back.
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        std::vector<glm::vec4> result(count);
        glGetNamedBufferSubData(sums.id(), 0, static_cast<GLsizeiptr>(count * sizeof(glm::vec4)),
                                result.data());
        glBindTextureUnit(kRadianceUnit, 0);
        glBindTextureUnit(kSkyUnit, 0);
        gl::check_error("HemiPlaneGatherer::gather");

        const float scale = static_cast<float>(glm::pi<double>() / coverage);
        for (std::size_t i = 0; i < count; ++i) {
            glm::vec3 e = glm::vec3(result[i]) * scale;
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
