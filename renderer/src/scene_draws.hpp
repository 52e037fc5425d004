#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "joint_palette.hpp"
#include "luxel/ecs/registry.hpp"
#include "luxel/runtime/program.hpp"
#include "mesh_cache.hpp"

namespace luxel::lighting {
class LightingSystem;
}

namespace luxel::renderer {

/// What the G-buffer pass writes for one primitive (shaders/render/gbuffer.frag).
struct DrawMaterial {
    glm::vec3 albedo{0.0f};  ///< diffuse albedo factor, clamped to [0, 1]
    /// Sampled with TEXCOORD_0 and multiplied into `albedo` per pixel: the base-colour texture,
    /// or MeshCache's 1x1 white one (never 0, so every draw can bind it unconditionally).
    GLuint base_color_texture = 0;
    glm::vec3 emission{0.0f};  ///< emitted radiance W/(m^2 sr), times the AreaLight's scale
    /// Sampled with TEXCOORD_0 and multiplied into `emission` per pixel: the emissive texture
    /// or the white one, as base_color_texture.
    GLuint emissive_texture = 0;
    glm::vec4 specular{0.0f};  ///< rgb: Fresnel F0 (0: not specular), a: transmission
    /// Glass: rgb what a view ray through it keeps besides Fresnel (the tint per surface
    /// crossed, the inside's absorption), a: the surfaces it crosses (1 or 2). Zero otherwise.
    glm::vec4 transmittance{0.0f};
    /// A closed solid's own optics, for a view ray that ends on a surface inside it: the tint of
    /// one surface, and the volume's attenuation (rgb colour, a: distance in metres, 0: clear).
    glm::vec3 tint{1.0f};
    glm::vec4 attenuation{1.0f, 1.0f, 1.0f, 0.0f};
    glm::vec2 lightmap{-1.0f, 0.0f};  ///< IIM page layer (-1: none), 1 = holds irradiance
    float ior = 1.5f;
    bool double_sided = false;
};

struct DrawPrimitive {
    const GpuPrimitive* range = nullptr;
    DrawMaterial material;
};

/// One entity's mesh placed in the world.
struct DrawItem {
    ecs::Entity entity;
    const GpuMesh* mesh = nullptr;
    glm::mat4 model{1.0f};
    glm::mat3 normal_matrix{1.0f};
    Bounds bounds;          ///< world space
    std::size_t first = 0;  ///< into DrawList::primitives
    std::size_t count = 0;
    bool specular = false;  ///< any primitive has a specular material
    bool mirrored = false;  ///< the model matrix flips winding (negative determinant)
    /// A mesh skinned in the vertex stage (GpuMesh::skinned): its joint matrices in
    /// DrawList::joints, from `first_joint`, `joint_count` of them. -1: not skinned.
    std::int32_t first_joint = -1;
    std::int32_t joint_count = 0;
    GLuint joint_buffer = 0;
};

/// glTF's doubleSided for the passes that see surfaces (G-buffer, probes): a single-sided
/// primitive shows only its front, so of two faces back to back in one plane (a wall between
/// two rooms) the one facing the camera is drawn, not whichever wins the depth test; a
/// double-sided one shows both sides. Shadow maps keep both sides (either side casts).
void cull_as_material(const DrawItem& item, const DrawMaterial& material);

/// Sets `program`'s u_model and u_normal_matrix (render/mesh.vert) to the item's, and its joint
/// matrices for a skinned mesh (render/skinning.glsl), and binds its mesh: what every pass
/// drawing scene meshes does before an item's primitives.
void bind_draw_item(const gl::Program& program, const DrawItem& item);

struct DrawList {
    std::vector<DrawItem> items;
    std::vector<DrawPrimitive> primitives;
    Bounds bounds;        ///< of everything
    JointPalette joints;  ///< the skinned items' joint matrices, uploaded with the list
};

/// Builds this frame's draw list from every MeshInstance entity: its mesh from the cache, its
/// world matrix, and per primitive the material and the IIM page of its light-mapped surface
/// (PhotonWorld numbers surfaces by (entity, primitive); the page is
/// IlluminationMaps::aim().surface_page, the content IlluminationMaps::surfaces()).
///
/// `specular_pass` says whether specular materials are shaded by the specular pass (then their
/// diffuse albedo and light map are zero: their look is the reflection); without it they are
/// drawn as diffuse surfaces of their base colour. `skin_on_gpu`: skinned meshes are drawn
/// from their bind mesh and this frame's joint matrices (FrameSettings::gpu_skinning).
void build_draw_list(ecs::Registry& registry, const lighting::LightingSystem& lighting,
                     MeshCache& meshes, std::uint64_t frame, bool specular_pass, bool skin_on_gpu,
                     DrawList& out);

}  // namespace luxel::renderer
