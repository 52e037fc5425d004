#include "luxel/lighting/core/ray_scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <string>

#include <embree3/rtcore.h>

#include "luxel/runtime/error.hpp"
#include "luxel/runtime/log.hpp"

namespace luxel::lighting {
namespace {

struct DeviceDeleter {
    void operator()(RTCDevice device) const { rtcReleaseDevice(device); }
};
struct SceneDeleter {
    void operator()(RTCScene scene) const { rtcReleaseScene(scene); }
};
using DeviceHandle = std::unique_ptr<RTCDeviceTy, DeviceDeleter>;
using SceneHandle = std::unique_ptr<RTCSceneTy, SceneDeleter>;

void report_embree_error(void* /*user*/, RTCError code, const char* message) {
    log::error("Embree error ", static_cast<int>(code), ": ", message != nullptr ? message : "");
}

glm::vec3 transform_point(const glm::mat4& m, const glm::vec3& p) {
    return glm::vec3(m * glm::vec4(p, 1.0f));
}

void check_mesh(const TriangleMesh& mesh) {
    if (mesh.indices.size() % 3 != 0) {
        throw Error("RayScene: index count is not a multiple of 3");
    }
    const std::size_t triangles = mesh.triangle_count();
    if (mesh.surface_ids.size() != triangles || mesh.material_ids.size() != triangles) {
        throw Error("RayScene: need one surface id and one material id per triangle");
    }
    if ((!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size()) ||
        (!mesh.lightmap_uvs.empty() && mesh.lightmap_uvs.size() != mesh.positions.size())) {
        throw Error("RayScene: normals and light-map UVs need one entry per position");
    }
    for (std::uint32_t index : mesh.indices) {
        if (index >= mesh.positions.size()) {
            throw Error("RayScene: index " + std::to_string(index) + " out of range");
        }
    }
    for (const auto& p : mesh.positions) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
            throw Error("RayScene: non-finite vertex position");
        }
    }
}

/// Adds a triangle geometry holding `mesh` (positions already in the scene's space) to `scene`
/// and returns its geometry id. Embree copies into buffers it allocates with the padding its
/// SIMD loads need past the last vertex.
unsigned attach_triangles(RTCDevice device, RTCScene scene, const std::vector<glm::vec3>& positions,
                          const std::vector<std::uint32_t>& indices, bool refit = false) {
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (refit) {
        // A dynamic object's BVH is refitted when RayScene::deform moves its vertices (the
        // first build is a normal one, and Embree reads this only once deform has made the
        // object's scene two-level): a skinned mesh's new pose costs a pass over its nodes
        // instead of a rebuild.
        rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_REFIT);
    }
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), positions.size()));
    auto* triangles = static_cast<std::uint32_t*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(std::uint32_t), indices.size() / 3));
    if (vertices == nullptr || triangles == nullptr) {
        rtcReleaseGeometry(geometry);
        throw Error("RayScene: Embree could not allocate geometry buffers");
    }
    std::memcpy(vertices, positions.data(), positions.size() * sizeof(glm::vec3));
    std::memcpy(triangles, indices.data(), indices.size() * sizeof(std::uint32_t));
    rtcCommitGeometry(geometry);
    const unsigned id = rtcAttachGeometry(scene, geometry);
    rtcReleaseGeometry(geometry);  // the scene holds it now
    return id;
}

}  // namespace

glm::vec3 offset_ray_origin(const glm::vec3& position, const glm::vec3& geometric_normal,
                            float side) {
    // Intersection error grows with the magnitude of the coordinates (a few float ulps of the
    // largest one), so the step does too: 2^-18 of the largest coordinate is ~30 times the
    // error Embree's watertight test leaves, and still a millionth-scale step. The 1 nm floor
    // only matters at the origin itself, where the error is tiny as well.
    constexpr float kRelativeStep = 1.0f / 262144.0f;
    constexpr float kSmallestStep = 1e-9f;
    const glm::vec3 magnitude = glm::abs(position);
    const float largest = std::max(magnitude.x, std::max(magnitude.y, magnitude.z));
    const float step = std::max(largest * kRelativeStep, kSmallestStep);
    return position + (side * step) * geometric_normal;
}

struct RayScene::Impl {
    struct Object {
        ObjectId id = kNoObject;
        TriangleMesh mesh;
        glm::mat4 transform{1.0f};
        glm::mat3 normal_matrix{1.0f};
        bool dynamic = false;
        SceneHandle own_scene;   // dynamic objects only
        bool deforming = false;  // deformed once: its own scene is two-level, refitted
        std::uint64_t deformations = 0;
        unsigned instance_id = RTC_INVALID_GEOMETRY_ID;
    };

    DeviceHandle device;
    // Two scenes, each traced on its own (intersect_any_face): the static geometry as one flat
    // BVH, and a top level that instances the dynamic objects. Tracing the static BVH directly
    // rather than as an instance of the top level keeps a photon's ray at raw Embree speed
    // where most of a level is; the top level holds only what moves, so its low-quality
    // rebuilds stay cheap and its traversal short, and it is skipped when nothing moves.
    SceneHandle static_scene;
    SceneHandle top;
    std::map<ObjectId, Object> objects;  // owns the objects; the tables below point into it
    // Object lookup for every hit, as flat tables: static geometry id -> object and top-level
    // instance id -> object (null once the object is removed). A std::map lookup per hit was
    // a measurable part of a photon's trace.
    std::vector<const Object*> static_owner;
    std::vector<const Object*> instance_owner;
    std::size_t dynamic_count = 0;      // dynamic objects now
    std::size_t committed_dynamic = 0;  // dynamic objects in the top level as last committed
    ObjectId next_id = 0;
    bool static_dirty = true;
    bool top_dirty = true;
    glm::vec3 lo{std::numeric_limits<float>::max()};
    glm::vec3 hi{std::numeric_limits<float>::lowest()};
    std::uint64_t static_rebuilds = 0;
    std::uint64_t top_commits = 0;

    Impl() : device(rtcNewDevice(nullptr)) {
        if (!device) {
            throw Error("RayScene: Embree device creation failed (error " +
                        std::to_string(static_cast<int>(rtcGetDeviceError(nullptr))) + ")");
        }
        rtcSetDeviceErrorFunction(device.get(), report_embree_error, nullptr);
        top.reset(rtcNewScene(device.get()));
        // The top level is rebuilt whenever something moves: favour build speed.
        rtcSetSceneFlags(top.get(),
                         RTC_SCENE_FLAG_DYNAMIC | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
        rtcSetSceneBuildQuality(top.get(), RTC_BUILD_QUALITY_LOW);
    }

    Object& get(ObjectId id) {
        const auto found = objects.find(id);
        if (found == objects.end()) {
            throw Error("RayScene: unknown object " + std::to_string(id));
        }
        return found->second;
    }
    const Object& get(ObjectId id) const { return const_cast<Impl*>(this)->get(id); }

    void rebuild_static() {
        static_scene.reset(rtcNewScene(device.get()));
        rtcSetSceneFlags(static_scene.get(), RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
        rtcSetSceneBuildQuality(static_scene.get(), RTC_BUILD_QUALITY_HIGH);
        static_owner.clear();
        for (const auto& [id, object] : objects) {
            if (object.dynamic) {
                continue;
            }
            const unsigned geometry = attach_triangles(device.get(), static_scene.get(),
                                                       object.mesh.positions, object.mesh.indices);
            if (geometry >= static_owner.size()) {
                static_owner.resize(geometry + 1, nullptr);
            }
            static_owner[geometry] = &object;
        }
        rtcCommitScene(static_scene.get());
        ++static_rebuilds;
    }

    /// The hit record of a finished query (static BVH, then top level); nullopt for a miss or
    /// an object removed since the last commit.
    [[nodiscard]] std::optional<RayHit> make_hit(const RTCRayHit& query) const;

    void recompute_bounds() {
        lo = glm::vec3(std::numeric_limits<float>::max());
        hi = glm::vec3(std::numeric_limits<float>::lowest());
        for (const auto& [id, object] : objects) {
            for (const auto& p : object.mesh.positions) {
                const glm::vec3 w = object.dynamic ? transform_point(object.transform, p) : p;
                lo = glm::min(lo, w);
                hi = glm::max(hi, w);
            }
        }
    }
};

std::optional<RayHit> RayScene::Impl::make_hit(const RTCRayHit& query) const {
    if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
        return std::nullopt;
    }
    // The static BVH is traced directly, so only an instance hit names an instance.
    const Impl::Object* found = nullptr;
    const unsigned instance = query.hit.instID[0];
    if (instance != RTC_INVALID_GEOMETRY_ID) {
        found = instance < instance_owner.size() ? instance_owner[instance] : nullptr;
    } else if (query.hit.geomID < static_owner.size()) {
        found = static_owner[query.hit.geomID];
    }
    if (found == nullptr) {
        return std::nullopt;  // geometry removed since the last commit
    }
    const Impl::Object& object = *found;
    const TriangleMesh& mesh = object.mesh;
    const std::uint32_t triangle = query.hit.primID;
    const std::uint32_t i0 = mesh.indices[3 * triangle];
    const std::uint32_t i1 = mesh.indices[3 * triangle + 1];
    const std::uint32_t i2 = mesh.indices[3 * triangle + 2];
    const float u = query.hit.u;
    const float v = query.hit.v;
    const float w = 1.0f - u - v;

    RayHit hit;
    hit.distance = query.ray.tfar;
    hit.object = object.id;
    hit.triangle = triangle;
    hit.surface = mesh.surface_ids[triangle];
    hit.material = mesh.material_ids[triangle];
    hit.barycentric = glm::vec2(u, v);
    // Interpolating the triangle's own vertices is more precise than origin + t * direction
    // far from the origin; it puts the point on the triangle's plane.
    const glm::vec3 local =
        w * mesh.positions[i0] + u * mesh.positions[i1] + v * mesh.positions[i2];
    const glm::vec3 face = glm::cross(mesh.positions[i1] - mesh.positions[i0],
                                      mesh.positions[i2] - mesh.positions[i0]);
    if (object.dynamic) {
        hit.position = transform_point(object.transform, local);
        hit.geometric_normal = glm::normalize(object.normal_matrix * face);
    } else {
        hit.position = local;
        hit.geometric_normal = glm::normalize(face);
    }
    if (!mesh.normals.empty()) {
        const glm::vec3 n = w * mesh.normals[i0] + u * mesh.normals[i1] + v * mesh.normals[i2];
        const glm::vec3 world = object.dynamic ? object.normal_matrix * n : n;
        const float length = glm::length(world);
        hit.shading_normal = length > 0.0f ? world / length : hit.geometric_normal;
    } else {
        hit.shading_normal = hit.geometric_normal;
    }
    if (!mesh.lightmap_uvs.empty()) {
        hit.lightmap_uv =
            w * mesh.lightmap_uvs[i0] + u * mesh.lightmap_uvs[i1] + v * mesh.lightmap_uvs[i2];
    }
    return hit;
}

RayScene::RayScene() : impl_(std::make_unique<Impl>()) {}
RayScene::~RayScene() = default;
RayScene::RayScene(RayScene&&) noexcept = default;
RayScene& RayScene::operator=(RayScene&&) noexcept = default;

ObjectId RayScene::add_object(TriangleMesh mesh, const glm::mat4& transform, bool dynamic) {
    check_mesh(mesh);
    Impl::Object object;
    object.dynamic = dynamic;
    object.transform = dynamic ? transform : glm::mat4(1.0f);
    object.normal_matrix = glm::transpose(glm::inverse(glm::mat3(object.transform)));
    if (!dynamic) {
        // Bake static geometry into world space once.
        const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(transform)));
        for (auto& p : mesh.positions) {
            p = transform_point(transform, p);
        }
        for (auto& n : mesh.normals) {
            n = glm::normalize(normal_matrix * n);
        }
    }
    object.mesh = std::move(mesh);
    const ObjectId id = impl_->next_id++;
    object.id = id;
    if (dynamic) {
        object.own_scene.reset(rtcNewScene(impl_->device.get()));
        rtcSetSceneFlags(object.own_scene.get(), RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
        attach_triangles(impl_->device.get(), object.own_scene.get(), object.mesh.positions,
                         object.mesh.indices, true);
        rtcCommitScene(object.own_scene.get());
        RTCGeometry instance = rtcNewGeometry(impl_->device.get(), RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(instance, object.own_scene.get());
        rtcSetGeometryTransform(instance, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR,
                                &object.transform[0][0]);
        rtcCommitGeometry(instance);
        object.instance_id = rtcAttachGeometry(impl_->top.get(), instance);
        rtcReleaseGeometry(instance);
        impl_->top_dirty = true;
    } else {
        impl_->static_dirty = true;
    }
    const Impl::Object& added = impl_->objects.emplace(id, std::move(object)).first->second;
    if (added.dynamic) {
        if (added.instance_id >= impl_->instance_owner.size()) {
            impl_->instance_owner.resize(added.instance_id + 1, nullptr);
        }
        impl_->instance_owner[added.instance_id] = &added;
        ++impl_->dynamic_count;
    }
    return id;
}

void RayScene::set_transform(ObjectId id, const glm::mat4& transform) {
    Impl::Object& object = impl_->get(id);
    if (!object.dynamic) {
        throw Error("RayScene: object " + std::to_string(id) + " is static and cannot move");
    }
    object.transform = transform;
    object.normal_matrix = glm::transpose(glm::inverse(glm::mat3(transform)));
    RTCGeometry instance = rtcGetGeometry(impl_->top.get(), object.instance_id);
    rtcSetGeometryTransform(instance, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &transform[0][0]);
    rtcCommitGeometry(instance);
    impl_->top_dirty = true;
}

void RayScene::deform(ObjectId id, std::span<const glm::vec3> positions,
                      std::span<const glm::vec3> normals) {
    Impl::Object& object = impl_->get(id);
    if (!object.dynamic) {
        throw Error("RayScene: object " + std::to_string(id) + " is static and cannot deform");
    }
    if (positions.size() != object.mesh.positions.size() ||
        normals.size() != object.mesh.normals.size()) {
        throw Error("RayScene: deforming object " + std::to_string(id) + " with " +
                    std::to_string(positions.size()) + " vertices, not its " +
                    std::to_string(object.mesh.positions.size()));
    }
    for (const glm::vec3& p : positions) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
            throw Error("RayScene: a deformed vertex is not finite");
        }
    }
    ++object.deformations;
    // A caller may pass the object's own arrays back (mesh()): copying a range onto itself is
    // not allowed, and not needed.
    if (positions.data() != object.mesh.positions.data()) {
        std::copy(positions.begin(), positions.end(), object.mesh.positions.begin());
    }
    if (normals.data() != object.mesh.normals.data()) {
        std::copy(normals.begin(), normals.end(), object.mesh.normals.begin());
    }
    RTCGeometry geometry = rtcGetGeometry(object.own_scene.get(), 0);
    auto* vertices =
        static_cast<float*>(rtcGetGeometryBufferData(geometry, RTC_BUFFER_TYPE_VERTEX, 0));
    std::memcpy(vertices, positions.data(), positions.size() * sizeof(glm::vec3));
    rtcUpdateGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0);
    if (!object.deforming) {
        // Embree honours a geometry's REFIT quality only in a two-level dynamic scene (a low
        // quality alone still rebuilt: 2.0 ms against 2.1 for 19.6k triangles, measured before the
        // flag was added, and 0.24 ms with it, luxel_skinning_bench); objects that never deform
        // keep the single level.
        rtcSetSceneFlags(object.own_scene.get(),
                         RTC_SCENE_FLAG_DYNAMIC | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
        rtcSetSceneBuildQuality(object.own_scene.get(), RTC_BUILD_QUALITY_LOW);
        object.deforming = true;
    }
    rtcCommitGeometry(geometry);
    rtcCommitScene(object.own_scene.get());
    // The instance's bounds changed with its BVH: the instance and the top level are
    // committed again.
    rtcCommitGeometry(rtcGetGeometry(impl_->top.get(), object.instance_id));
    impl_->top_dirty = true;
}

void RayScene::remove_object(ObjectId id) {
    Impl::Object& object = impl_->get(id);
    // Rays until the next commit still meet the object's triangles: its table entry goes null
    // so they miss it rather than read a freed object.
    if (object.dynamic) {
        rtcDetachGeometry(impl_->top.get(), object.instance_id);
        impl_->instance_owner[object.instance_id] = nullptr;
        --impl_->dynamic_count;
        impl_->top_dirty = true;
    } else {
        std::replace(impl_->static_owner.begin(), impl_->static_owner.end(),
                     static_cast<const Impl::Object*>(&object),
                     static_cast<const Impl::Object*>(nullptr));
        impl_->static_dirty = true;
    }
    impl_->objects.erase(id);
}

std::uint64_t RayScene::deformations(ObjectId id) const {
    return impl_->get(id).deformations;
}

bool RayScene::contains(ObjectId id) const {
    return impl_->objects.count(id) != 0;
}
bool RayScene::is_dynamic(ObjectId id) const {
    return impl_->get(id).dynamic;
}

void RayScene::commit() {
    const bool changed = impl_->static_dirty || impl_->top_dirty;
    if (impl_->static_dirty) {
        impl_->rebuild_static();
        impl_->static_dirty = false;
    }
    if (impl_->top_dirty) {
        rtcCommitScene(impl_->top.get());
        impl_->committed_dynamic = impl_->dynamic_count;
        impl_->top_dirty = false;
        ++impl_->top_commits;
    }
    if (changed) {
        impl_->recompute_bounds();
    }
}

namespace {

/// A context filter that lets only front faces (the side a triangle winds towards) be hit.
void reject_back_faces(const RTCFilterFunctionNArguments* args) {
    for (unsigned lane = 0; lane < args->N; ++lane) {
        if (args->valid[lane] == 0) {
            continue;
        }
        const float facing =
            RTCHitN_Ng_x(args->hit, args->N, lane) * RTCRayN_dir_x(args->ray, args->N, lane) +
            RTCHitN_Ng_y(args->hit, args->N, lane) * RTCRayN_dir_y(args->ray, args->N, lane) +
            RTCHitN_Ng_z(args->hit, args->N, lane) * RTCRayN_dir_z(args->ray, args->N, lane);
        if (facing > 0.0f) {
            args->valid[lane] = 0;
        }
    }
}

}  // namespace

std::optional<RayHit> RayScene::intersect(const glm::vec3& origin, const glm::vec3& direction,
                                          float max_distance) const {
    return facing_the_ray(origin, direction,
                          intersect_any_face(origin, direction, max_distance, false));
}

std::optional<RayHit> RayScene::facing_the_ray(const glm::vec3& origin, const glm::vec3& direction,
                                               std::optional<RayHit> hit) const {
    // Two faces back to back in one plane (a zero-thickness wall seen from either room) are
    // hit at the same distance, and Embree may report either. When it reports the back face,
    // look again for a front face at that distance: the side the ray came from is the one it
    // sees. Only back-face hits (glass interiors, the backs of walls) pay for the second ray.
    if (hit && glm::dot(hit->geometric_normal, direction) > 0.0f) {
        const float reach = hit->distance * (1.0f + 1e-4f) + 1e-30f;
        if (auto front = intersect_any_face(origin, direction, reach, true);
            front && front->distance >= hit->distance * (1.0f - 1e-4f)) {
            return front;
        }
    }
    return hit;
}

namespace {

/// Sets up `query` in place for a closest-hit query (building a temporary and copying it in
/// made the stream's setup stall on store forwarding: a tenth of the samples of a `perf record`
/// of the sandbox level's warm-up).
void set_ray_query(RTCRayHit& query, const glm::vec3& origin, const glm::vec3& direction,
                   float max_distance) {
    query.ray.org_x = origin.x;
    query.ray.org_y = origin.y;
    query.ray.org_z = origin.z;
    query.ray.tnear = 0.0f;
    query.ray.dir_x = direction.x;
    query.ray.dir_y = direction.y;
    query.ray.dir_z = direction.z;
    query.ray.time = 0.0f;
    query.ray.tfar = max_distance;
    query.ray.mask = 0xFFFFFFFFu;
    query.ray.id = 0;
    query.ray.flags = 0;
    query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    query.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

}  // namespace

std::optional<RayHit> RayScene::intersect_any_face(const glm::vec3& origin,
                                                   const glm::vec3& direction, float max_distance,
                                                   bool front_faces_only) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    if (front_faces_only) {
        context.filter = reject_back_faces;
    }
    RTCRayHit query;
    set_ray_query(query, origin, direction, max_distance);
    // The static BVH first, then the moving objects with the ray cut at the static hit: Embree
    // writes the hit only for a closer one, so the query ends with the closest of both.
    if (impl_->static_scene) {
        rtcIntersect1(impl_->static_scene.get(), &context, &query);
    }
    if (impl_->committed_dynamic > 0) {
        rtcIntersect1(impl_->top.get(), &context, &query);
    }
    return impl_->make_hit(query);
}

void RayScene::intersect_from(const glm::vec3& origin, std::span<const glm::vec3> directions,
                              float max_distance, std::span<std::optional<RayHit>> hits) const {
    const std::size_t count = std::min(directions.size(), hits.size());
    // One stream per call, kept per thread: the gather calls this for every texel.
    thread_local std::vector<RTCRayHit> queries;
    queries.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
        set_ray_query(queries[i], origin, directions[i], max_distance);
    }
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    // Embree's coherent-stream flag was measured and made the gather 1.7 times slower on
    // Debian's Embree 3.13 build (luxel_maps_bench Gather): the default, incoherent mode, is
    // used.
    const auto stream = static_cast<unsigned>(count);
    if (impl_->static_scene && stream > 0) {
        rtcIntersect1M(impl_->static_scene.get(), &context, queries.data(), stream,
                       sizeof(RTCRayHit));
    }
    if (impl_->committed_dynamic > 0 && stream > 0) {
        rtcIntersect1M(impl_->top.get(), &context, queries.data(), stream, sizeof(RTCRayHit));
    }
    for (std::size_t i = 0; i < count; ++i) {
        hits[i] = impl_->make_hit(queries[i]);
        if (hits[i] && glm::dot(hits[i]->geometric_normal, directions[i]) > 0.0f) {
            hits[i] = facing_the_ray(origin, directions[i], hits[i]);
        }
    }
}

bool RayScene::occluded(const glm::vec3& origin, const glm::vec3& direction,
                        float max_distance) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray{};
    ray.org_x = origin.x;
    ray.org_y = origin.y;
    ray.org_z = origin.z;
    ray.dir_x = direction.x;
    ray.dir_y = direction.y;
    ray.dir_z = direction.z;
    ray.tnear = 0.0f;
    ray.tfar = max_distance;
    ray.mask = 0xFFFFFFFFu;
    // Embree marks an occluded ray by setting tfar to -inf.
    if (impl_->static_scene) {
        rtcOccluded1(impl_->static_scene.get(), &context, &ray);
    }
    if (ray.tfar >= 0.0f && impl_->committed_dynamic > 0) {
        rtcOccluded1(impl_->top.get(), &context, &ray);
    }
    return ray.tfar < 0.0f;
}

glm::vec3 RayScene::bounds_min() const {
    return impl_->lo;
}
glm::vec3 RayScene::bounds_max() const {
    return impl_->hi;
}
std::size_t RayScene::object_count() const {
    return impl_->objects.size();
}

std::vector<ObjectId> RayScene::objects() const {
    std::vector<ObjectId> ids;
    ids.reserve(impl_->objects.size());
    for (const auto& entry : impl_->objects) {
        ids.push_back(entry.first);
    }
    return ids;
}
std::size_t RayScene::triangle_count() const {
    std::size_t total = 0;
    for (const auto& [id, object] : impl_->objects) {
        total += object.mesh.triangle_count();
    }
    return total;
}
std::uint64_t RayScene::static_rebuilds() const {
    return impl_->static_rebuilds;
}
std::uint64_t RayScene::top_level_commits() const {
    return impl_->top_commits;
}
const TriangleMesh& RayScene::mesh(ObjectId id) const {
    return impl_->get(id).mesh;
}

HitTriangle RayScene::triangle(const RayHit& hit) const {
    const Impl::Object& object = impl_->get(hit.object);
    const TriangleMesh& mesh = object.mesh;
    const std::size_t first = 3 * static_cast<std::size_t>(hit.triangle);
    if (first + 2 >= mesh.indices.size()) {
        throw Error("RayScene::triangle: object " + std::to_string(hit.object) +
                    " has no triangle " + std::to_string(hit.triangle));
    }
    HitTriangle out;
    out.has_normals = !mesh.normals.empty();
    for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = mesh.indices[first + static_cast<std::size_t>(k)];
        // Static objects are stored in world space; dynamic ones move by their transform.
        out.positions[k] = object.dynamic ? transform_point(object.transform, mesh.positions[v])
                                          : mesh.positions[v];
        if (out.has_normals) {
            out.normals[k] =
                object.dynamic ? object.normal_matrix * mesh.normals[v] : mesh.normals[v];
        }
    }
    return out;
}
glm::mat4 RayScene::transform(ObjectId id) const {
    return impl_->get(id).transform;
}

}  // namespace luxel::lighting
