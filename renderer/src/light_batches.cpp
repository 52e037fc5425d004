#include "light_batches.hpp"

#include <algorithm>
#include <array>
#include <cstdint>

namespace luxel::renderer {
namespace {

constexpr GLuint kBlockBinding = 0;
constexpr GLuint kCubeUnit = 4;
constexpr GLuint kMapUnit = 8;

/// std140 mirror of the LightBatch block.
struct GpuLightBatch {
    std::array<GpuLight, LightBatches::kLightsPerBatch> lights{};
    std::array<std::int32_t, 4> count{};
};

gl::Texture unused_shadow_map(GLenum target) {
    gl::Texture texture = gl::Texture::create(target);
    glTextureStorage3D(texture.id(), 1, GL_DEPTH_COMPONENT32F, 1, 1,
                       target == GL_TEXTURE_CUBE_MAP_ARRAY ? 6 : 1);
    glTextureParameteri(texture.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(texture.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return texture;
}

}  // namespace

LightBatches::LightBatches()
    : block_(gl::Buffer::create(sizeof(GpuLightBatch))),
      unused_cube_(unused_shadow_map(GL_TEXTURE_CUBE_MAP_ARRAY)),
      unused_map_(unused_shadow_map(GL_TEXTURE_2D_ARRAY)) {}

std::uint32_t LightBatches::shadow_shapes(const std::vector<FrameLight>& lights, std::size_t batch,
                                          const ShadowMaps& shadows) {
    std::uint32_t shapes = 0;
    const std::size_t first = batch * kLightsPerBatch;
    for (std::size_t i = first; i < std::min(first + kLightsPerBatch, lights.size()); ++i) {
        if (const ShadowMap* map = shadows.find(lights[i].entity); map != nullptr && map->valid) {
            shapes |= map->kind == ShadowKind::Cube ? kCubeShadows : kMapShadows;
        }
    }
    return shapes;
}

void LightBatches::bind(const std::vector<FrameLight>& lights, std::size_t batch,
                        const ShadowMaps& shadows) {
    GpuLightBatch data;
    const std::size_t first = batch * kLightsPerBatch;
    const std::size_t count =
        first < lights.size() ? std::min(kLightsPerBatch, lights.size() - first) : 0;
    data.count[0] = static_cast<std::int32_t>(count);
    for (std::size_t slot = 0; slot < count; ++slot) {
        const FrameLight& light = lights[first + slot];
        GpuLight& gpu = data.lights[slot];
        gpu.position_kind = glm::vec4(light.position, static_cast<float>(light.kind));
        gpu.direction_far = glm::vec4(light.direction, 0.0f);
        gpu.intensity_shadow = glm::vec4(light.intensity, -1.0f);
        gpu.params = glm::vec4(light.cos_inner, light.cos_outer, 0.0f, 0.0f);
        if (const ShadowMap* map = shadows.find(light.entity); map != nullptr && map->valid) {
            ShadowMaps::describe(*map, gpu);  // its layer in intensity_shadow.w
        }
    }
    glBindTextureUnit(kCubeUnit,
                      shadows.cube_array() != 0 ? shadows.cube_array() : unused_cube_.id());
    glBindTextureUnit(kMapUnit, shadows.map_array() != 0 ? shadows.map_array() : unused_map_.id());
    block_.update(0, sizeof(data), &data);
    glBindBufferBase(GL_UNIFORM_BUFFER, kBlockBinding, block_.id());
}

}  // namespace luxel::renderer
