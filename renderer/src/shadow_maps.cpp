#include "shadow_maps.hpp"

#include "cube_faces.hpp"
#include "fill_budget.hpp"
#include "luxel/runtime/log.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace luxel::renderer {
namespace {

/// Rounds up to the next power of 1.25 so the far plane changes in steps, not with every
/// motion of the scene's bounds.
float round_up(float value) {
    const float step = std::log(1.25f);
    return std::exp(std::ceil(std::log(std::max(value, 1e-3f)) / step) * step);
}

glm::vec3 any_up(const glm::vec3& axis) {
    return std::abs(axis.y) < 0.99f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
}

float farthest_corner(const Bounds& bounds, const glm::vec3& from) {
    const glm::vec3 d = glm::max(glm::abs(bounds.lo - from), glm::abs(bounds.hi - from));
    return glm::length(d);
}

/// The state a light's map depends on, computed for this frame.
struct Placement {
    glm::mat4 matrix{1.0f};
    glm::vec3 origin{0.0f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f};
    float far = 1.0f;
    float texel = 0.0f;
};

Placement place(const FrameLight& light, const Bounds& scene, int size) {
    Placement p;
    p.direction = light.direction;
    if (light.shadow == ShadowKind::Ortho) {
        const glm::vec3 centre_raw = scene.empty() ? glm::vec3(0.0f) : 0.5f * (scene.lo + scene.hi);
        const float radius =
            round_up(scene.empty() ? 1.0f : 0.5f * glm::length(scene.hi - scene.lo) + 1e-3f);
        // The centre snaps to a grid of radius / 8 for the same reason the radius is rounded.
        const float grid = radius / 8.0f;
        const glm::vec3 centre = glm::round(centre_raw / grid) * grid;
        const float r = radius + grid;  // the snapped sphere still holds the scene
        p.origin = centre - light.direction * r;
        p.far = 2.0f * r;
        p.texel = 2.0f * r / static_cast<float>(size);
        const glm::mat4 view = glm::lookAt(p.origin, centre, any_up(light.direction));
        p.matrix = glm::ortho(-r, r, -r, r, -0.01f * r, 1.01f * p.far) * view;
        return p;
    }
    p.origin = light.position;
    p.far = round_up(scene.empty() ? 1.0f : farthest_corner(scene, light.position) * 1.01f);
    if (light.shadow == ShadowKind::Cube) {
        // A 90 degree face spans 2 units at unit distance.
        p.texel = 2.0f / static_cast<float>(size);
        return p;
    }
    // A perspective map over the outer cone plus a two-texel rim for the PCF taps.
    const float half = std::min(light.outer_cone * (1.0f + 4.0f / static_cast<float>(size)), 1.5f);
    p.texel = 2.0f * std::tan(half) / static_cast<float>(size);
    const float near = std::max(1e-3f * p.far, 1e-3f);
    const glm::mat4 view =
        glm::lookAt(light.position, light.position + light.direction, any_up(light.direction));
    p.matrix = glm::perspective(2.0f * half, 1.0f, near, 1.01f * p.far) * view;
    return p;
}

/// Draws every caster in reach into one view (a 2D map or a cube face) whose world-to-clip
/// matrix is `view_projection`, within that view's FillBudget; returns the budget spent.
FillBudget draw_casters(const DrawList& draws, const gl::Program& program, const ShadowMap& map,
                        const glm::mat4& view_projection) {
    FillBudget budget(static_cast<double>(map.size) * static_cast<double>(map.size));
    draw_in_view(
        draws, view_projection, map.size, map.size, budget,
        [&](const DrawItem& item) {
            // Out of the light's reach: casts nothing it can see.
            return map.kind == ShadowKind::Ortho || item.bounds.touches_sphere(map.origin, map.far);
        },
        [&](const DrawItem& item) {
            bind_draw_item(program, item);
            // Both sides cast (no culling), but shadow.frag needs to know which side the light
            // sees: glTF's front faces wind counter-clockwise, a mirroring transform turns them.
            glFrontFace(item.mirrored ? GL_CW : GL_CCW);
        },
        [&](const DrawItem&, const DrawPrimitive& primitive) {
            program.set("u_single_sided", primitive.material.double_sided ? 0 : 1);
            draw_primitive(*primitive.range);
        });
    return budget;
}

}  // namespace

ShadowMaps::ShadowMaps(int cube_size, int map_size)
    : cube_size_(std::max(cube_size, 1)),
      map_size_(std::max(map_size, 1)),
      cube_layers_(GL_TEXTURE_CUBE_MAP_ARRAY, cube_size_),
      map_layers_(GL_TEXTURE_2D_ARRAY, map_size_) {}

void ShadowMaps::invalidate(const Bounds& bounds) {
    for (auto& [entity, map] : maps_) {
        if (map.kind == ShadowKind::Ortho || bounds.touches_sphere(map.origin, map.far)) {
            map.valid = false;
        }
    }
}

ShadowMap ShadowMaps::allocate(ShadowKind kind) {
    ShadowMap map;
    map.kind = kind;
    map.size = kind == ShadowKind::Cube ? cube_size_ : map_size_;
    map.layer = layers(kind).acquire();
    map.framebuffer = gl::Framebuffer::create();
    glNamedFramebufferDrawBuffer(map.framebuffer.id(), GL_NONE);
    glNamedFramebufferReadBuffer(map.framebuffer.id(), GL_NONE);
    gl::check_error("ShadowMaps allocate");
    return map;
}

void ShadowMaps::free(ShadowMap& map) {
    layers(map.kind).release(map.layer);
    map.layer = -1;
}

void ShadowMaps::clear() {
    for (auto& [entity, map] : maps_) {
        free(map);
    }
    maps_.clear();
}

void ShadowMaps::note_budget(ShadowMap& map, const FillBudget& budget) {
    if (budget.skipped() == 0) {
        return;
    }
    skipped_casters_ += budget.skipped();
    if (!map.warned) {
        map.warned = true;
        log::warn("a shadow map's casters would cover about ", budget.wanted(), " texels of one ",
                  map.size, "x", map.size, " view (", FillBudget::kLayers,
                  " layers allowed): the level stacks geometry on itself; ", budget.skipped(),
                  " primitives are left out of this light's shadow");
    }
}

void ShadowMaps::render(ShadowMap& map, const DrawList& draws, const gl::Program& program) {
    const GLuint fbo = map.framebuffer.id();
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    glViewport(0, 0, map.size, map.size);
    program.set("u_light_position", map.origin);
    program.set("u_light_direction", map.direction);
    program.set("u_planar", map.kind == ShadowKind::Ortho ? 1 : 0);
    program.set("u_far", map.far);
    program.set("u_texel", map.texel);
    const float clear_depth = 1.0f;
    // Attached at every draw: the array is a new texture after it grows.
    const GLuint array = layers(map.kind).id();
    if (map.kind != ShadowKind::Cube) {
        glNamedFramebufferTextureLayer(fbo, GL_DEPTH_ATTACHMENT, array, 0, map.layer);
        map.framebuffer.check_complete("shadow map");
        glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &clear_depth);
        program.set("u_view_projection", map.matrix);
        note_budget(map, draw_casters(draws, program, map, map.matrix));
        map.valid = true;
        return;
    }
    const float near = std::max(1e-3f * map.far, 1e-3f);
    const glm::mat4 projection =
        glm::perspective(glm::half_pi<float>(), 1.0f, near, 1.75f * map.far);
    for (int face = 0; face < 6; ++face) {
        glNamedFramebufferTextureLayer(fbo, GL_DEPTH_ATTACHMENT, array, 0, 6 * map.layer + face);
        map.framebuffer.check_complete("shadow cube face");
        glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &clear_depth);
        const glm::mat4 view_projection = projection * cube_face_view(map.origin, face);
        program.set("u_view_projection", view_projection);
        note_budget(map, draw_casters(draws, program, map, view_projection));
    }
    map.valid = true;
}

std::size_t ShadowMaps::update(const std::vector<FrameLight>& lights, const DrawList& draws,
                               const gl::Program& program) {
    std::set<ecs::Entity> present;
    for (const FrameLight& light : lights) {
        present.insert(light.entity);
    }
    for (auto it = maps_.begin(); it != maps_.end();) {
        if (present.contains(it->first)) {
            ++it;
        } else {
            free(it->second);
            it = maps_.erase(it);
        }
    }

    std::size_t rendered = 0;
    for (const FrameLight& light : lights) {
        auto found = maps_.find(light.entity);
        if (found != maps_.end() && found->second.kind != light.shadow) {
            free(found->second);
            maps_.erase(found);  // a spot widened past kWideSpot: a different kind of map
            found = maps_.end();
        }
        if (found == maps_.end()) {
            found = maps_.emplace(light.entity, allocate(light.shadow)).first;
        }
        ShadowMap& map = found->second;
        const Placement placement = place(light, draws.bounds, map.size);
        const bool moved = placement.origin != map.origin || placement.far != map.far ||
                           (map.kind != ShadowKind::Cube && (placement.direction != map.direction ||
                                                             light.outer_cone != map.outer_cone));
        if (map.valid && !moved) {
            continue;
        }
        map.origin = placement.origin;
        map.direction = placement.direction;
        map.outer_cone = light.outer_cone;
        map.far = placement.far;
        map.texel = placement.texel;
        map.matrix = placement.matrix;
        render(map, draws, program);
        ++rendered;
    }
    return rendered;
}

const ShadowMap* ShadowMaps::find(ecs::Entity light) const {
    const auto found = maps_.find(light);
    return found == maps_.end() ? nullptr : &found->second;
}

void ShadowMaps::describe(const ShadowMap& map, GpuLight& light) {
    if (map.kind == ShadowKind::Ortho) {
        light.position_kind = glm::vec4(map.origin, light.position_kind.w);
    }
    light.direction_far.w = map.far;
    light.params.z = map.texel;
    light.params.w = static_cast<float>(map.kind);
    light.shadow_matrix = map.matrix;
    light.intensity_shadow.w = static_cast<float>(map.layer);
    // The shader walks from a 2D map's texel centres back into the world (the receiver plane's
    // depth at each tap); one inverse per light a frame instead of one per pixel.
    light.shadow_inverse =
        map.kind == ShadowKind::Cube ? glm::mat4(1.0f) : glm::inverse(map.matrix);
}

}  // namespace luxel::renderer
