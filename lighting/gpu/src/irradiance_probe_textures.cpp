#include "luxel/lighting/gpu/irradiance_probe_textures.hpp"

#include <cmath>
#include <vector>

#include <glm/glm.hpp>

namespace luxel::lighting {
namespace {

/// One probe as shaders/render/irradiance_probes.glsl's ProbeRecord reads it (std430).
struct ProbeRecord {
    glm::vec4 position;  ///< xyz world position with the offset, w 1 when active
    glm::vec4 irradiance[kShCoefficients];
};
static_assert(sizeof(ProbeRecord) == 10 * sizeof(glm::vec4));

/// Copies one probe's tile (rows of `side` texels) into its place in an atlas's texels.
template <class Texel, class Value>
void copy_tile(std::span<const Value> tile, int side, std::size_t index, int tiles_per_row,
               int atlas_width, std::vector<Texel>& atlas, Texel (*convert)(const Value&)) {
    const auto per_row = static_cast<std::size_t>(tiles_per_row);
    const auto n = static_cast<std::size_t>(side);
    const std::size_t tile_x = (index % per_row) * n;
    const std::size_t tile_y = (index / per_row) * n;
    for (std::size_t y = 0; y < n && y * n < tile.size(); ++y) {
        for (std::size_t x = 0; x < n; ++x) {
            atlas[(tile_y + y) * static_cast<std::size_t>(atlas_width) + tile_x + x] =
                convert(tile[y * n + x]);
        }
    }
}

}  // namespace

void IrradianceProbeTextures::sync(const IrradianceProbes* probes) {
    if (probes == nullptr || probes->probes().empty()) {
        records_.reset();
        depth_.reset();
        irradiance_.reset();
        count_ = 0;
        source_ = nullptr;
        return;
    }
    const std::span<const ProbeState> states = probes->probes();
    const bool same = probes == source_ && probes->grid() == grid_ && count_ == states.size() &&
                      probes->settings().basis == basis_;
    if (same && probes->version() == version_) {
        return;
    }
    if (!same) {
        grid_ = probes->grid();
        count_ = states.size();
        tiles_per_row_ =
            std::max(1, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count_)))));
        const int rows = static_cast<int>((count_ + static_cast<std::size_t>(tiles_per_row_) - 1) /
                                          static_cast<std::size_t>(tiles_per_row_));
        records_ = gl::Buffer::create(count_ * sizeof(ProbeRecord));
        // create_2d's textures filter bilinearly and clamp at the edges, as the atlases are read.
        depth_ = gl::Texture::create_2d(GL_RG32F, tiles_per_row_ * kProbeDepthTile,
                                        rows * kProbeDepthTile);
        basis_ = probes->settings().basis;
        irradiance_ =
            basis_ == ProbeBasis::Octahedral
                ? gl::Texture::create_2d(GL_RGBA16F, tiles_per_row_ * kProbeIrradianceTile,
                                         rows * kProbeIrradianceTile)
                : gl::Texture{};
        source_ = probes;
    }
    std::vector<ProbeRecord> records(count_);
    std::vector<glm::vec2> depth(static_cast<std::size_t>(depth_.width()) *
                                 static_cast<std::size_t>(depth_.height()));
    std::vector<glm::vec4> irradiance(irradiance_
                                          ? static_cast<std::size_t>(irradiance_.width()) *
                                                static_cast<std::size_t>(irradiance_.height())
                                          : 0);
    for (std::size_t i = 0; i < count_; ++i) {
        const ProbeState& state = states[i];
        records[i].position =
            glm::vec4(grid_.position(grid_.cell(i)) + state.offset, state.active ? 1.0f : 0.0f);
        for (std::size_t c = 0; c < kShCoefficients; ++c) {
            records[i].irradiance[c] = glm::vec4(state.irradiance.c[c], 0.0f);
        }
        copy_tile<glm::vec2, glm::vec2>(state.depth, kProbeDepthTile, i, tiles_per_row_,
                                        depth_.width(), depth,
                                        [](const glm::vec2& v) { return v; });
        if (irradiance_) {
            copy_tile<glm::vec4, glm::vec3>(
                state.irradiance_map, kProbeIrradianceTile, i, tiles_per_row_, irradiance_.width(),
                irradiance, [](const glm::vec3& v) {
                    constexpr float kHalfMax = 65504.0f;  // the largest finite half float
                    return glm::vec4(glm::min(v, glm::vec3(kHalfMax)), 1.0f);
                });
        }
    }
    records_.update(0, records.size() * sizeof(ProbeRecord), records.data());
    glTextureSubImage2D(depth_.id(), 0, 0, 0, depth_.width(), depth_.height(), GL_RG, GL_FLOAT,
                        depth.data());
    if (irradiance_) {
        glTextureSubImage2D(irradiance_.id(), 0, 0, 0, irradiance_.width(), irradiance_.height(),
                            GL_RGBA, GL_FLOAT, irradiance.data());
    }
    gl::check_error("IrradianceProbeTextures upload");
    version_ = probes->version();
    ++uploads_;
}

void IrradianceProbeTextures::bind(const gl::Program& program) const {
    program.set("u_probes_on", count_ > 0 ? 1 : 0);
    if (count_ == 0) {
        return;
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kProbeBlock, records_.id());
    glBindTextureUnit(kDepthUnit, depth_.id());
    // The shader samples the irradiance atlas only with the octahedral basis; the unit is
    // bound either way so that no sampler reads an unbound unit.
    glBindTextureUnit(kIrradianceUnit, irradiance_ ? irradiance_.id() : depth_.id());
    program.set("u_probe_basis", basis_ == ProbeBasis::Octahedral ? 0 : 1);
    program.set("u_probe_origin", grid_.origin);
    program.set("u_probe_spacing", grid_.spacing);
    program.set("u_probe_counts", glm::vec3(grid_.counts));
    program.set("u_probe_tiles_per_row", tiles_per_row_);
}

}  // namespace luxel::lighting
