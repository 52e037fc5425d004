#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

/// The Embree ray scene the photon tracer and the CPU gather shoot rays into.
///
/// Structure: every static object is baked into world space and goes into one Embree scene
/// (one BVH), which rays traverse directly; each dynamic object has its own scene in object
/// space, instanced with its transform by a top-level scene of the dynamic objects alone, so
/// moving an object updates one instance transform and recommits only the small top level. A
/// ray meets the static BVH first and then the top level, cut at the static hit (skipped when
/// nothing is dynamic): static geometry, most of a level, is traced at flat-BVH speed.
namespace luxel::lighting {

using ObjectId = std::uint32_t;
inline constexpr ObjectId kNoObject = std::numeric_limits<ObjectId>::max();

/// Triangles with what a hit must report. Per-vertex normals and light-map UVs are optional
/// (empty); per-triangle surface and material ids are required (one per triangle).
struct TriangleMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec2> lightmap_uvs;
    std::vector<std::uint32_t> indices;       ///< three per triangle
    std::vector<std::int32_t> surface_ids;    ///< per triangle; -1: not light-mapped
    std::vector<std::uint32_t> material_ids;  ///< per triangle; the caller's material table

    [[nodiscard]] std::size_t triangle_count() const { return indices.size() / 3; }
};

/// What a ray hit, in world space.
struct RayHit {
    float distance = 0.0f;
    glm::vec3 position{0.0f};
    glm::vec3 geometric_normal{0.0f};  ///< unit, facing the side the triangle winds towards
    glm::vec3 shading_normal{0.0f};    ///< unit, interpolated (geometric when no normals)
    glm::vec2 lightmap_uv{0.0f};
    /// The hit's weights of the triangle's second and third vertices (the first's is
    /// 1 - x - y): what a caller that keeps its own per-vertex data interpolates it with.
    glm::vec2 barycentric{0.0f};
    std::int32_t surface = -1;
    std::uint32_t material = 0;
    ObjectId object = kNoObject;
    std::uint32_t triangle = 0;
};

/// The world-space corners and vertex normals (not normalised; the normal matrix applied) of
/// the triangle a hit lies on; `has_normals` false for a mesh without vertex normals.
struct HitTriangle {
    glm::vec3 positions[3];
    glm::vec3 normals[3];
    bool has_normals = false;
};

/// Moves a ray origin off a surface along its geometric normal by 2^-18 of the position's largest
/// coordinate (not a fixed epsilon), so a ray leaving a hit does not re-hit the same surface at
/// any scene scale, from millimetres to kilometres. `side` is +1 to leave on the
/// normal's side, -1 for the other (refraction).
[[nodiscard]] glm::vec3 offset_ray_origin(const glm::vec3& position,
                                          const glm::vec3& geometric_normal, float side = 1.0f);

class RayScene {
  public:
    RayScene();
    ~RayScene();
    RayScene(const RayScene&) = delete;
    RayScene& operator=(const RayScene&) = delete;
    RayScene(RayScene&&) noexcept;
    RayScene& operator=(RayScene&&) noexcept;

    /// Adds an object. A static object is baked into the static BVH with `transform` (rebuilt on
    /// the next commit); a dynamic one gets its own BVH and an instance whose transform
    /// set_transform changes. Throws luxel::Error for malformed meshes.
    ObjectId add_object(TriangleMesh mesh, const glm::mat4& transform, bool dynamic);
    /// Moves a dynamic object (throws for a static one: static means it does not move).
    void set_transform(ObjectId object, const glm::mat4& transform);
    /// New vertex positions and normals (object space, as many as it has) for a dynamic
    /// object whose triangles stay the same (a skinned mesh's new pose): its BVH is refitted,
    /// not rebuilt. Throws for a static object, another vertex count, or a non-finite vertex.
    void deform(ObjectId object, std::span<const glm::vec3> positions,
                std::span<const glm::vec3> normals);
    void remove_object(ObjectId object);
    /// How many times deform() has changed the object's vertices: what a mirror of the scene
    /// (the GPU gather's geometry) compares to know its copy is stale.
    [[nodiscard]] std::uint64_t deformations(ObjectId object) const;
    [[nodiscard]] bool contains(ObjectId object) const;
    [[nodiscard]] bool is_dynamic(ObjectId object) const;

    /// Makes every change visible to rays: rebuilds the static BVH if static objects changed,
    /// and recommits the top level. Tracing before the first commit sees an empty scene.
    void commit();

    /// Closest hit along origin + t direction for t in (0, max_distance]. `direction` need not
    /// be unit; distances are in units of |direction|. Of two faces coincident at the closest
    /// distance (back to back in one plane), the one facing the ray. Thread-safe between commits.
    [[nodiscard]] std::optional<RayHit> intersect(
        const glm::vec3& origin, const glm::vec3& direction,
        float max_distance = std::numeric_limits<float>::infinity()) const;
    /// The closest hit of each ray from one origin (a texel's gather rays), as intersect()
    /// gives it, traced as one Embree stream (rtcIntersect1M): cheaper per ray than one call
    /// each (17% on the gather, docs/PERFORMANCE.md). hits[i] answers directions[i] (the shorter
    /// span decides how many). Thread-safe between commits.
    void intersect_from(const glm::vec3& origin, std::span<const glm::vec3> directions,
                        float max_distance, std::span<std::optional<RayHit>> hits) const;
    /// Whether anything lies along the ray in (0, max_distance).
    [[nodiscard]] bool occluded(const glm::vec3& origin, const glm::vec3& direction,
                                float max_distance) const;

    /// World-space bounds of everything committed (empty box: min > max).
    [[nodiscard]] glm::vec3 bounds_min() const;
    [[nodiscard]] glm::vec3 bounds_max() const;
    [[nodiscard]] std::size_t object_count() const;
    /// Every object, in id order (what a rasterizer mirroring this scene uploads).
    [[nodiscard]] std::vector<ObjectId> objects() const;
    [[nodiscard]] std::size_t triangle_count() const;
    /// Counters since construction: static BVH rebuilds and top-level commits.
    [[nodiscard]] std::uint64_t static_rebuilds() const;
    [[nodiscard]] std::uint64_t top_level_commits() const;

    /// The geometry of an object as added (object space for dynamic, world space for static).
    [[nodiscard]] const TriangleMesh& mesh(ObjectId object) const;
    /// The triangle `hit` lies on, in world space (one lookup; the photon differentials' normal
    /// derivative reads it at every specular hit). Throws for an object no longer in the scene.
    [[nodiscard]] HitTriangle triangle(const RayHit& hit) const;
    [[nodiscard]] glm::mat4 transform(ObjectId object) const;

  private:
    /// `hit` unless it is a back face with a front face at the same distance (that one).
    [[nodiscard]] std::optional<RayHit> facing_the_ray(const glm::vec3& origin,
                                                       const glm::vec3& direction,
                                                       std::optional<RayHit> hit) const;
    [[nodiscard]] std::optional<RayHit> intersect_any_face(const glm::vec3& origin,
                                                           const glm::vec3& direction,
                                                           float max_distance,
                                                           bool front_faces_only) const;

    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace luxel::lighting
