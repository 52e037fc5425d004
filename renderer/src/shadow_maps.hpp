#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include <glm/glm.hpp>

#include "frame_lights.hpp"
#include "luxel/runtime/gl_objects.hpp"
#include "luxel/runtime/program.hpp"
#include "scene_draws.hpp"
#include "shadow_layers.hpp"

namespace luxel::renderer {

/// One light's shadow map and the light state it was rendered for.
struct ShadowMap {
    ShadowKind kind = ShadowKind::Cube;
    int size = 0;
    int layer = -1;  ///< its layer of ShadowMaps' cube or 2D array (cube_array(), map_array())
    gl::Framebuffer framebuffer;
    glm::mat4 matrix{1.0f};  ///< world to clip (2D maps)
    glm::vec3 origin{0.0f};  ///< the light (ortho: the map's plane origin)
    glm::vec3 direction{0.0f, 0.0f, -1.0f};
    float outer_cone = 0.0f;
    float far = 1.0f;     ///< metres that depth 1 stands for
    float texel = 0.0f;   ///< texel size per metre of distance (ortho: metres)
    bool valid = false;   ///< rendered for the current light state and casters
    bool warned = false;  ///< its casters have overrun a FillBudget once (said once a map)
};

class FillBudget;

/// Shadow maps for the enabled punctual lights (linear depth, shaders/render/shadow.frag).
///
/// A map is rendered again only when it is invalid: new, its light's placement or shape
/// changed (position, direction for 2D maps, cone, or the far distance / scene sphere that the
/// scene's bounds set, rounded up in 25% steps so small motions at the scene's edge do not
/// count), or invalidate() was told of a caster change inside its range (the sphere of radius
/// `far` around a point or spot light; anywhere for a directional light). A light that is
/// switched off keeps no map.
class ShadowMaps {
  public:
    ShadowMaps(int cube_size, int map_size);

    /// A mesh was added, removed or moved; `bounds` is where it was or is (world space).
    void invalidate(const Bounds& bounds);
    /// Allocates maps for new lights, frees those of lights gone or switched off, and renders
    /// the invalid ones with `program` (shaders/render/shadow.*). Returns the maps rendered.
    std::size_t update(const std::vector<FrameLight>& lights, const DrawList& draws,
                       const gl::Program& program);
    /// Frees every map.
    void clear();

    [[nodiscard]] const ShadowMap* find(ecs::Entity light) const;
    /// The cube-map array (DEPTH_COMPONENT32F, compare mode on) holding every cube map, and the
    /// 2D array holding the spot and sun maps; 0 while no map of that shape exists.
    [[nodiscard]] GLuint cube_array() const { return cube_layers_.id(); }
    [[nodiscard]] GLuint map_array() const { return map_layers_.id(); }
    /// Fills the shadow fields of a light record (direction_far.w, params.z, params.w, matrix,
    /// position for ortho maps).
    static void describe(const ShadowMap& map, GpuLight& light);
    [[nodiscard]] std::size_t count() const { return maps_.size(); }
    /// Caster primitives left out of a view by its FillBudget, since construction.
    [[nodiscard]] std::uint64_t skipped_casters() const { return skipped_casters_; }

  private:
    ShadowMap allocate(ShadowKind kind);
    void free(ShadowMap& map);
    ShadowLayers& layers(ShadowKind kind) {
        return kind == ShadowKind::Cube ? cube_layers_ : map_layers_;
    }
    void render(ShadowMap& map, const DrawList& draws, const gl::Program& program);
    void note_budget(ShadowMap& map, const FillBudget& budget);

    int cube_size_;
    int map_size_;
    ShadowLayers cube_layers_;
    ShadowLayers map_layers_;
    std::map<ecs::Entity, ShadowMap> maps_;
    std::uint64_t skipped_casters_ = 0;
};

}  // namespace luxel::renderer
