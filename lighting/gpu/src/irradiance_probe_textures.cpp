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

}  // namespace

void IrradianceProbeTextures::sync(const IrradianceProbes* probes) {
    if (probes == nullptr || probes->probes().empty()) {
        records_.reset();
        depth_.reset();
        count_ = 0;
        source_ = nullptr;
        return;
    }
    const std::span<const ProbeState> states = probes->probes();
    const bool same = probes == source_ && probes->grid() == grid_ && count_ == states.size();
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
        depth_ = gl::Texture::create_2d(GL_RG32F, tiles_per_row_ * kProbeDepthTile,
                                        rows * kProbeDepthTile);
        glTextureParameteri(depth_.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(depth_.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(depth_.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(depth_.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        source_ = probes;
    }
    std::vector<ProbeRecord> records(count_);
    std::vector<glm::vec2> texels(static_cast<std::size_t>(depth_.width()) *
                                  static_cast<std::size_t>(depth_.height()));
    for (std::size_t i = 0; i < count_; ++i) {
        const ProbeState& state = states[i];
        records[i].position =
            glm::vec4(grid_.position(grid_.cell(i)) + state.offset, state.active ? 1.0f : 0.0f);
        for (std::size_t c = 0; c < kShCoefficients; ++c) {
            records[i].irradiance[c] = glm::vec4(state.irradiance.c[c], 0.0f);
        }
        const std::size_t tile_x = (i % static_cast<std::size_t>(tiles_per_row_)) * kProbeDepthTile;
        const std::size_t tile_y = (i / static_cast<std::size_t>(tiles_per_row_)) * kProbeDepthTile;
        for (std::size_t y = 0; y < static_cast<std::size_t>(kProbeDepthTile); ++y) {
            for (std::size_t x = 0; x < static_cast<std::size_t>(kProbeDepthTile); ++x) {
                texels[(tile_y + y) * static_cast<std::size_t>(depth_.width()) + tile_x + x] =
                    state.depth[y * kProbeDepthTile + x];
            }
        }
    }
    records_.update(0, records.size() * sizeof(ProbeRecord), records.data());
    glTextureSubImage2D(depth_.id(), 0, 0, 0, depth_.width(), depth_.height(), GL_RG, GL_FLOAT,
                        texels.data());
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
    program.set("u_probe_origin", grid_.origin);
    program.set("u_probe_spacing", grid_.spacing);
    program.set("u_probe_counts", glm::vec3(grid_.counts));
    program.set("u_probe_tiles_per_row", tiles_per_row_);
}

}  // namespace luxel::lighting
