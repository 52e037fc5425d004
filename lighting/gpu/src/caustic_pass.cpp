#include "luxel/lighting/gpu/caustic_pass.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "caustic_photon_buffer.hpp"
#include "caustics/caustic_interface.h"
#include "luxel/runtime/error.hpp"
#include "luxel/runtime/gl_state_guard.hpp"
#include "luxel/runtime/program.hpp"
#include "luxel/runtime/shader_library.hpp"

// Pixel area. A pixel spans A_img = 4 / (P00 P11 W H) of the image plane at unit view depth.
// The ray through image point p = (x, y, -1) (view space, per unit depth) meets a surface of
// unit normal n at view depth z; the surface patch seen through the pixel has area
// dA = dw r^2 / cos(theta) with dw = A_img / |p|^3, r = z |p| and cos(theta) = |n . p| / |p|,
// so dA = A_img z^2 / |n . p|. On a plane parallel to the image plane n . p = 1 everywhere on
// screen: (2 z tan(fov/2) / H)^2 is exact there, not only at the centre. The splat divides by
// the full expression when account_for_orientation is set, n from the depth buffer's slope.

namespace luxel::lighting {
namespace {

// Binding points shared with shaders/caustics/* (caustic_interface.h, which both include).
constexpr GLuint kPhotonsBinding = CAUSTIC_PHOTONS_BINDING;
constexpr GLuint kTileFlagsBinding = CAUSTIC_TILE_FLAGS_BINDING;
constexpr GLuint kControlBinding = CAUSTIC_CONTROL_BINDING;
constexpr GLuint kTileListBinding = CAUSTIC_TILE_LIST_BINDING;
constexpr GLuint kWeightsBinding = CAUSTIC_WEIGHTS_BINDING;
constexpr GLuint kDepthUnit = CAUSTIC_DEPTH_UNIT;
constexpr GLuint kSplatUnit = CAUSTIC_SPLAT_UNIT;
constexpr GLuint kOutputImage = CAUSTIC_OUTPUT_IMAGE;
static_assert(kCausticTileSize == CAUSTIC_TILE);
static_assert(kPhotonsBinding < kWeightsBinding && kWeightsBinding - kPhotonsBinding == 4,
              "unbind() walks the storage bindings from photons to weights");

// The photon buffer holds CausticPhoton as it is: its layout must be std430's struct Photon.
static_assert(sizeof(CausticPhoton) == CAUSTIC_PHOTON_SIZE);
static_assert(offsetof(CausticPhoton, position) == CAUSTIC_PHOTON_POSITION);
// `surface` and `footprint` are bitfields of the word at CAUSTIC_PHOTON_SURFACE (offsetof cannot
// name them): position ends there and power starts after it; a test checks their bits.
static_assert(offsetof(CausticPhoton, position) + sizeof(glm::vec3) == CAUSTIC_PHOTON_SURFACE);
static_assert(offsetof(CausticPhoton, power) == CAUSTIC_PHOTON_POWER);
static_assert(offsetof(CausticPhoton, lightmap_uv_bits) == CAUSTIC_PHOTON_LIGHTMAP_UV);

/// std430 CausticControl of shaders/caustics/caustic_tiles.glsl (caustic_interface.h).
struct Control {
    GLuint dispatch_x = 0;
    GLuint dispatch_y = 1;
    GLuint dispatch_z = 1;
    GLuint photons_splatted = 0;
    GLuint tiles_marked = 0;
    GLuint tiles_filtered = 0;
};
static_assert(sizeof(Control) == CAUSTIC_CONTROL_SIZE);

void validate(const CausticPassSettings& s) {
    if (s.kernel_radius < 0 || s.kernel_radius > kMaxCausticKernelRadius) {
        throw Error("CausticPassSettings.kernel_radius must be in [0, " +
                    std::to_string(kMaxCausticKernelRadius) + "], got " +
                    std::to_string(s.kernel_radius));
    }
    if ((s.kernel == CausticKernel::WorldCone || s.kernel == CausticKernel::MipLevels ||
         s.kernel == CausticKernel::PhotonFootprints) &&
        (!(s.world_radius > 0.0f) || !std::isfinite(s.world_radius))) {
        throw Error("CausticPassSettings.world_radius must be positive and finite");
    }
    if (s.kernel == CausticKernel::MipLevels &&
        (!(s.mip_min_photons >= 1.0f) || !std::isfinite(s.mip_min_photons))) {
        throw Error("CausticPassSettings.mip_min_photons must be at least 1 and finite");
    }
    if (s.kernel == CausticKernel::PhotonFootprints &&
        (!(s.footprint_scale > 0.0f) || !std::isfinite(s.footprint_scale) ||
         !(s.footprint_min_pixels >= 1.0f) || !std::isfinite(s.footprint_min_pixels) ||
         !(s.footprint_max_pixels >= s.footprint_min_pixels) ||
         !std::isfinite(s.footprint_max_pixels))) {
        throw Error(
            "CausticPassSettings: footprint_scale must be positive and finite, "
            "footprint_min_pixels at least 1 and footprint_max_pixels at least that, both "
            "finite");
    }
    if (!(s.min_cos > 0.0f) || !(s.min_cos <= 1.0f)) {
        throw Error("CausticPassSettings.min_cos must be in (0, 1]");
    }
    if (!(s.depth_bias_relative >= 0.0f) || !(s.depth_bias_absolute >= 0.0f)) {
        throw Error("CausticPassSettings depth biases must be non-negative");
    }
}

int tiles_for(int pixels) {
    return (pixels + kCausticTileSize - 1) / kCausticTileSize;
}

/// Restores what gl::StateGuard does not cover: the blend function and equation.
class BlendGuard {
  public:
    BlendGuard() {
        glGetIntegerv(GL_BLEND_SRC_RGB, &src_rgb_);
        glGetIntegerv(GL_BLEND_DST_RGB, &dst_rgb_);
        glGetIntegerv(GL_BLEND_SRC_ALPHA, &src_alpha_);
        glGetIntegerv(GL_BLEND_DST_ALPHA, &dst_alpha_);
        glGetIntegerv(GL_BLEND_EQUATION_RGB, &eq_rgb_);
        glGetIntegerv(GL_BLEND_EQUATION_ALPHA, &eq_alpha_);
    }
    ~BlendGuard() {
        glBlendFuncSeparate(static_cast<GLenum>(src_rgb_), static_cast<GLenum>(dst_rgb_),
                            static_cast<GLenum>(src_alpha_), static_cast<GLenum>(dst_alpha_));
        glBlendEquationSeparate(static_cast<GLenum>(eq_rgb_), static_cast<GLenum>(eq_alpha_));
    }
    BlendGuard(const BlendGuard&) = delete;
    BlendGuard& operator=(const BlendGuard&) = delete;

  private:
    GLint src_rgb_ = GL_ONE;
    GLint dst_rgb_ = GL_ZERO;
    GLint src_alpha_ = GL_ONE;
    GLint dst_alpha_ = GL_ZERO;
    GLint eq_rgb_ = GL_FUNC_ADD;
    GLint eq_alpha_ = GL_FUNC_ADD;
};

}  // namespace

CausticCamera CausticCamera::perspective(const glm::mat4& view, float vertical_fov,
                                         glm::ivec2 viewport, float near, float far) {
    CausticCamera camera;
    camera.view = view;
    camera.viewport = viewport;
    const float aspect = static_cast<float>(viewport.x) / static_cast<float>(viewport.y);
    camera.projection = glm::perspective(vertical_fov, aspect, near, far);
    return camera;
}

double caustic_pixel_area(const CausticCamera& camera, double view_depth) {
    const double p00 = static_cast<double>(camera.projection[0][0]);
    const double p11 = static_cast<double>(camera.projection[1][1]);
    const double image_area = 4.0 / (std::abs(p00 * p11) * static_cast<double>(camera.viewport.x) *
                                     static_cast<double>(camera.viewport.y));
    return image_area * view_depth * view_depth;
}

struct CausticPass::Impl {
    CausticPassSettings settings;
    ShaderLibrary shaders;  // a copy: set_settings() rebuilds the filter
    glm::ivec2 size{0};
    glm::ivec2 tiles{0};

    gl::Program splat_program;
    gl::Program tile_program;
    gl::Program filter_program;
    gl::Texture splat;
    gl::Texture output;
    gl::Framebuffer framebuffer;
    gl::VertexArray empty_vertex_array;  // vertex pulling: the core profile still wants a VAO
    gl::Buffer tile_flags;
    gl::Buffer tile_list;
    gl::Buffer control;
    gl::Buffer weights;
    std::array<gl::Query, 2> timers;
    CausticPhotonBuffer photons;

    CausticPassStats stats;
    bool stats_pending = false;
    bool timers_pending = false;
    bool output_dirty = true;  // the output may hold something other than zero

    Impl(const CausticPassSettings& s, glm::ivec2 viewport, const ShaderLibrary& library)
        : settings(s), shaders(library) {
        validate(settings);
        build_splat();
        tile_program = library.build({{ShaderStage::Compute, "caustics/tile_list.comp"}});
        build_filter();
        empty_vertex_array = gl::VertexArray::create();
        control = gl::Buffer::create(sizeof(Control));
        for (gl::Query& q : timers) {
            q = gl::Query::create(GL_TIME_ELAPSED);
        }
        resize(viewport);
        gl::check_error("CausticPass setup");
    }

    /// The footprint kernel spreads photons as it splats them: the filter only copies.
    [[nodiscard]] int reach_pixels() const {
        return photon_footprints() ? 0 : settings.kernel_radius;
    }
    [[nodiscard]] int reach_tiles() const { return tiles_for(reach_pixels()); }

    [[nodiscard]] bool mip() const { return settings.kernel == CausticKernel::MipLevels; }
    [[nodiscard]] bool photon_footprints() const {
        return settings.kernel == CausticKernel::PhotonFootprints;
    }

    void build_splat() {
        if (photon_footprints()) {
            splat_program =
                shaders.build({{ShaderStage::Vertex, "caustics/photon_footprints.vert"},
                               {ShaderStage::Geometry, "caustics/photon_footprints.geom"},
                               {ShaderStage::Fragment, "caustics/photon_footprints.frag"}});
        } else {
            splat_program = shaders.build({{ShaderStage::Vertex, "caustics/splat.vert"},
                                           {ShaderStage::Fragment, "caustics/splat.frag"}});
        }
    }
    /// Levels of the splat's mip chain: down to 1 x 1 for the mip kernel, else level 0 alone.
    [[nodiscard]] int splat_levels() const {
        if (!mip()) {
            return 1;
        }
        int levels = 1;
        for (int s = std::max(size.x, size.y); s > 1; s /= 2) {  // floor(log2) + 1 levels
            ++levels;
        }
        return levels;
    }

    void build_filter() {
        if (mip()) {
            filter_program = shaders.build({{ShaderStage::Compute, "caustics/mip_filter.comp"}});
            const float one = 1.0f;
            weights = gl::Buffer::create(sizeof(float), &one, 0);
            return;
        }
        const int mode = settings.tile_mode == CausticTileMode::Full       ? 0
                         : settings.tile_mode == CausticTileMode::EarlyOut ? 1
                                                                           : 2;
        const bool world = settings.kernel == CausticKernel::WorldCone;
        const std::string defines = "#define RADIUS " + std::to_string(reach_pixels()) +
                                    "\n#define MODE " + std::to_string(mode) + "\n#define WORLD " +
                                    (world ? "1" : "0") + "\n";
        filter_program = shaders.build({{ShaderStage::Compute, "caustics/filter.comp"}}, defines);
        if (photon_footprints()) {
            const float one = 1.0f;  // k = 0: the splat already holds irradiance
            weights = gl::Buffer::create(sizeof(float), &one, 0);
        } else if (!world) {
            const std::vector<float> w =
                caustic_kernel_weights(settings.kernel, settings.kernel_radius);
            weights = gl::Buffer::create(w.size() * sizeof(float), w.data(), 0);
        } else {
            // The shader declares the block; bind something valid.
            const float one = 1.0f;
            weights = gl::Buffer::create(sizeof(float), &one, 0);
        }
    }

    void resize(glm::ivec2 viewport) {
        if (viewport.x <= 0 || viewport.y <= 0) {
            throw Error("CausticPass: the viewport must be positive, got " +
                        std::to_string(viewport.x) + " x " + std::to_string(viewport.y));
        }
        size = viewport;
        tiles = {tiles_for(size.x), tiles_for(size.y)};
        splat = gl::Texture::create_2d(GL_RGBA32F, size.x, size.y, splat_levels());
        // The photon footprints' result is their splat: no output to allocate.
        output = photon_footprints() ? gl::Texture{}
                                     : gl::Texture::create_2d(GL_RGBA32F, size.x, size.y);
        for (const gl::Texture* t : {&splat, &output}) {
            if (t->id() != 0) {
                glTextureParameteri(t->id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
                glTextureParameteri(t->id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
            }
        }
        if (mip()) {
            // The mip filter reads a level bilinearly at each pixel's centre (textureLod).
            glTextureParameteri(splat.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_NEAREST);
            glTextureParameteri(splat.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
            glTextureParameteri(splat.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
            glTextureParameteri(splat.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        }
        framebuffer = gl::Framebuffer::create();
        framebuffer.attach(GL_COLOR_ATTACHMENT0, splat);
        framebuffer.check_complete("CausticPass splat buffer");
        const auto tile_count =
            static_cast<std::size_t>(tiles.x) * static_cast<std::size_t>(tiles.y);
        tile_flags = gl::Buffer::create(tile_count * sizeof(GLuint));
        tile_list = gl::Buffer::create(tile_count * sizeof(GLuint), nullptr, 0);
        clear_output();
    }

    /// The texture the frame reads: the photon footprints spread each photon as they splat
    /// it, so their splat buffer is the irradiance and no filter runs (a copy through the
    /// filter cost 7.8 ms of 9.6 over a 512 x 512 frame on llvmpipe).
    [[nodiscard]] GLuint result() const { return photon_footprints() ? splat.id() : output.id(); }

    void clear_output() {
        const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        glClearTexImage(result(), 0, GL_RGBA, GL_FLOAT, zero);
        output_dirty = false;
    }

    void set_uniforms(const CausticCamera& camera) {
        const glm::mat4 inverse_projection = glm::inverse(camera.projection);
        const auto area_scale = static_cast<float>(caustic_pixel_area(camera, 1.0));
        const int zero_to_one = camera.depth_zero_to_one ? 1 : 0;
        for (const gl::Program* p : {&splat_program, &tile_program, &filter_program}) {
            p->set("u_inverse_projection", inverse_projection);
            glProgramUniform2i(p->id(), p->uniform_location("u_viewport"), size.x, size.y);
            glProgramUniform2i(p->id(), p->uniform_location("u_tiles"), tiles.x, tiles.y);
            p->set("u_depth_zero_to_one", zero_to_one);
            p->set("u_reach", reach_tiles());
        }
        splat_program.set("u_view", camera.view);
        splat_program.set("u_projection", camera.projection);
        splat_program.set("u_area_scale", area_scale);
        splat_program.set("u_orientation", settings.account_for_orientation ? 1 : 0);
        splat_program.set("u_min_cos", settings.min_cos);
        splat_program.set("u_bias_relative", settings.depth_bias_relative);
        splat_program.set("u_bias_absolute", settings.depth_bias_absolute);
        if (photon_footprints()) {
            splat_program.set("u_pixel_size_scale", std::sqrt(area_scale));
            splat_program.set("u_footprint_scale", settings.footprint_scale);
            splat_program.set("u_min_pixels", settings.footprint_min_pixels);
            splat_program.set("u_max_pixels", settings.footprint_max_pixels);
            splat_program.set("u_max_radius", settings.world_radius);
        }
        if (mip()) {
            filter_program.set("u_min_photons", settings.mip_min_photons);
            filter_program.set("u_levels", splat_levels());
            filter_program.set("u_max_radius", settings.world_radius);
        } else {
            filter_program.set("u_world_radius", settings.world_radius);
        }
        filter_program.set("u_pixel_size_scale", std::sqrt(area_scale));
    }

    void render(const CausticCamera& camera, GLuint scene_depth) {
        if (camera.viewport != size) {
            resize(camera.viewport);
        }
        stats.photons_drawn = photons.photon_count();
        stats.photons_splatted = 0;
        stats.tiles_total = static_cast<std::uint32_t>(tiles.x * tiles.y);
        stats.tiles_marked = 0;
        stats.tiles_filtered = 0;
        stats.splat_ms = 0.0;
        stats.filter_ms = 0.0;
        stats.slices_uploaded = photons.slices_uploaded();
        stats.bytes_uploaded = photons.bytes_uploaded();
        stats_pending = false;
        timers_pending = false;
        if (photons.photon_count() == 0) {
            // Nothing to splat: the output is zero, cleared once rather than every frame.
            if (output_dirty) {
                clear_output();
            }
            return;
        }

        const gl::StateGuard guard;
        const BlendGuard blend_guard;
        set_uniforms(camera);

        glBeginQuery(GL_TIME_ELAPSED, timers[0].id());
        const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        glClearNamedFramebufferfv(framebuffer.id(), GL_COLOR, 0, zero);
        glClearNamedBufferData(tile_flags.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
        const Control initial{};
        control.update(0, sizeof(Control), &initial);

        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer.id());
        glViewport(0, 0, size.x, size.y);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_CULL_FACE);
        glDisable(GL_SCISSOR_TEST);
        glEnable(GL_BLEND);
        glBlendEquation(GL_FUNC_ADD);
        glBlendFunc(GL_ONE, GL_ONE);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPhotonsBinding, photons.buffer());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kTileFlagsBinding, tile_flags.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kControlBinding, control.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kTileListBinding, tile_list.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kWeightsBinding, weights.id());
        glBindTextureUnit(kDepthUnit, scene_depth);
        splat_program.use();
        glBindVertexArray(empty_vertex_array.id());
        glMultiDrawArrays(GL_POINTS, photons.firsts().data(), photons.counts().data(),
                          static_cast<GLsizei>(photons.counts().size()));
        glEndQuery(GL_TIME_ELAPSED);

        glBeginQuery(GL_TIME_ELAPSED, timers[1].id());
        // The splat's flag and counter writes must be visible to the compute passes.
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
        if (!photon_footprints()) {  // their splat is read as it is (result())
            filter();
        }
        // The output is read by texture fetches or image loads in the composition.
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                        GL_BUFFER_UPDATE_BARRIER_BIT);
        glEndQuery(GL_TIME_ELAPSED);

        glBindImageTexture(kOutputImage, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glBindTextureUnit(kDepthUnit, 0);
        glBindTextureUnit(kSplatUnit, 0);
        for (GLuint b = kPhotonsBinding; b <= kWeightsBinding; ++b) {
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, 0);
        }
        gl::check_error("CausticPass::render");
        output_dirty = true;
        stats_pending = true;
        timers_pending = true;
    }

    /// The screen-space filter from the splat buffer into the output, on the tiles that need
    /// it.
    void filter() {
        if (mip()) {
            // The chain of means the filter reads; every tile is filtered (a coarse level
            // reaches any distance), so the output needs no clearing.
            glGenerateTextureMipmap(splat.id());
            glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
        } else if (settings.tile_mode != CausticTileMode::Full) {
            // Tiles out of reach are not written this frame: they must read zero.
            const float clear[4] = {0.0f, 0.0f, 0.0f, 0.0f};
            glClearTexImage(output.id(), 0, GL_RGBA, GL_FLOAT, clear);
        }
        glBindTextureUnit(kSplatUnit, splat.id());
        glBindImageTexture(kOutputImage, output.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        if (settings.tile_mode == CausticTileMode::Indirect && !mip()) {
            tile_program.use();
            glDispatchCompute(static_cast<GLuint>((tiles.x + 7) / 8),
                              static_cast<GLuint>((tiles.y + 7) / 8), 1);
            glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
            filter_program.use();
            glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, control.id());
            glDispatchComputeIndirect(0);
            glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
        } else {
            filter_program.use();
            glDispatchCompute(static_cast<GLuint>(tiles.x), static_cast<GLuint>(tiles.y), 1);
        }
    }

    void read_back() {
        stats.slices_uploaded = photons.slices_uploaded();
        stats.bytes_uploaded = photons.bytes_uploaded();
        if (stats_pending) {
            Control c{};
            glGetNamedBufferSubData(control.id(), 0, sizeof(Control), &c);
            stats.photons_splatted = c.photons_splatted;
            stats.tiles_marked = c.tiles_marked;
            stats.tiles_filtered =
                photon_footprints()                                    ? 0
                : settings.tile_mode == CausticTileMode::Full || mip() ? stats.tiles_total
                : settings.tile_mode == CausticTileMode::EarlyOut      ? c.tiles_filtered
                                                                       : c.dispatch_x;
            stats_pending = false;
        }
        if (timers_pending) {
            GLuint64 ns[2] = {0, 0};
            glGetQueryObjectui64v(timers[0].id(), GL_QUERY_RESULT, &ns[0]);
            glGetQueryObjectui64v(timers[1].id(), GL_QUERY_RESULT, &ns[1]);
            stats.splat_ms = static_cast<double>(ns[0]) * 1e-6;
            stats.filter_ms = static_cast<double>(ns[1]) * 1e-6;
            timers_pending = false;
        }
    }
};

CausticPass::CausticPass(CausticPassSettings settings, glm::ivec2 viewport)
    : CausticPass(settings, viewport, ShaderLibrary{}) {}

CausticPass::CausticPass(CausticPassSettings settings, glm::ivec2 viewport,
                         const ShaderLibrary& shaders)
    : impl_(std::make_unique<Impl>(settings, viewport, shaders)) {}

CausticPass::~CausticPass() = default;
CausticPass::CausticPass(CausticPass&&) noexcept = default;
CausticPass& CausticPass::operator=(CausticPass&&) noexcept = default;

void CausticPass::upload(std::span<const CausticPhoton> photons) {
    impl_->photons.upload(photons);
}

void CausticPass::upload(std::span<const CausticPair> pairs) {
    impl_->photons.upload(pairs);
}

void CausticPass::render(const CausticCamera& camera, GLuint scene_depth) {
    impl_->render(camera, scene_depth);
}

const CausticPhotonBuffer& CausticPass::photon_buffer() const {
    return impl_->photons;
}

GLuint CausticPass::irradiance_texture() const {
    return impl_->result();
}

GLuint CausticPass::splat_texture() const {
    return impl_->splat.id();
}

void CausticPass::set_settings(const CausticPassSettings& settings) {
    validate(settings);
    const bool was_mip = impl_->mip();
    const bool was_footprints = impl_->photon_footprints();
    impl_->settings = settings;
    if (impl_->photon_footprints() != was_footprints) {
        impl_->build_splat();
    }
    impl_->build_filter();
    if (impl_->mip() != was_mip || impl_->photon_footprints() != was_footprints) {
        impl_->resize(impl_->size);  // the splat gains or drops its mip chain, the output
    }
}

const CausticPassSettings& CausticPass::settings() const {
    return impl_->settings;
}

const CausticPassStats& CausticPass::stats() {
    impl_->read_back();
    return impl_->stats;
}

}  // namespace luxel::lighting
