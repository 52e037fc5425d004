#pragma once

#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "luxel/scene/animation.hpp"
#include "luxel/scene/light.hpp"
#include "luxel/scene/skin.hpp"
#include "luxel/scene/sky.hpp"

/// The engine-side scene: what a glTF 2.0 file holds, in luxel's units and conventions, with
/// every index checked. Loaders produce it, writers consume it, and the lighting module turns it
/// into ECS entities. Indices refer into the Scene's own vectors; -1 means "none".
namespace luxel::scene {

/// One indexed triangle list. Attributes other than positions may be empty; when present they
/// have one entry per position.
struct Primitive {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec2> texcoords0;   ///< material textures
    std::vector<glm::vec2> texcoords1;   ///< light-map UVs (written by luxel-prep)
    std::vector<std::uint32_t> indices;  ///< three per triangle, each < positions.size()
    /// Skinning (JOINTS_0, WEIGHTS_0): up to four joints per vertex, as indices into the skin
    /// of the node that draws the mesh, and their weights, which the loader normalises to sum
    /// to 1. Both empty for a mesh no skin deforms.
    std::vector<glm::u16vec4> joints;
    std::vector<glm::vec4> weights;
    int material = -1;

    [[nodiscard]] std::size_t triangle_count() const { return indices.size() / 3; }
};

struct Mesh {
    std::string name;
    std::vector<Primitive> primitives;
};

/// An image referenced by a material, kept as encoded bytes (PNG or JPEG) so it round-trips.
struct Image {
    std::string name;
    std::string mime_type;  ///< "image/png" or "image/jpeg"
    std::vector<std::uint8_t> encoded;
};

/// glTF's metallic-roughness material with the extensions luxel reads. Colours are linear.
struct Material {
    std::string name;
    glm::vec4 base_color{1.0f};
    int base_color_image = -1;  ///< index into Scene::images, sampled with TEXCOORD_0
    float metallic = 1.0f;      ///< glTF defaults
    float roughness = 1.0f;
    glm::vec3 emissive{0.0f};  ///< emissiveFactor
    /// emissiveTexture: index into Scene::images, sampled with TEXCOORD_0 and multiplied by
    /// emissive (scene::triangle_emission integrates it per triangle for the lighting).
    int emissive_image = -1;
    float emissive_strength = 1.0f;  ///< KHR_materials_emissive_strength
    float transmission = 0.0f;       ///< KHR_materials_transmission
    float ior = 1.5f;                ///< KHR_materials_ior
    /// KHR_materials_volume. thickness (thicknessFactor, the mesh's own units) > 0 makes a
    /// transmissive primitive the boundary of a solid whose inside keeps
    /// attenuation_color^(distance / attenuation_distance) of the light crossing it
    /// (Beer-Lambert, scene/volume.hpp); 0 is glTF's thin wall, which absorbs nothing.
    float thickness = 0.0f;
    float attenuation_distance = std::numeric_limits<float>::infinity();  ///< metres
    glm::vec3 attenuation_color{1.0f};
    bool double_sided = false;

    /// Emitted radiance in W/(m^2 sr): emissive * emissive_strength (luxel reads glTF's
    /// unitless emissive as radiance, documented in docs/UNITS.md); an emissive texture
    /// multiplies it per point.
    [[nodiscard]] glm::vec3 emitted_radiance() const { return emissive * emissive_strength; }
    [[nodiscard]] bool is_emissive() const;
    /// Transmissive (transmission > 0), or a mirror (metallic 1, roughness < 0.1): the materials
    /// that make caustics.
    [[nodiscard]] bool is_specular() const;
};

struct Camera {
    std::string name;
    bool perspective = true;
    float yfov = 0.8f;  ///< radians (perspective)
    std::optional<float> aspect_ratio;
    float znear = 0.05f;
    std::optional<float> zfar;  ///< infinite when absent
    float xmag = 1.0f;          ///< orthographic half extents
    float ymag = 1.0f;
};

/// What luxel reads from a node's `extras.luxel` object (glTF has no place for it).
struct NodeFlags {
    /// Explicit "dynamic": true/false. Absent: dynamic when an animation targets the node or an
    /// ancestor (see Scene::is_dynamic).
    std::optional<bool> dynamic;
    /// The light starts switched off ("enabled": false).
    bool light_enabled = true;
    /// "light_radius": a point or spot light's sphere, metres (0: a point; docs/LEVELS.md).
    float light_radius = 0.0f;
    /// The whole `extras.luxel` object, for what a game adds beyond these.
    nlohmann::json raw = nlohmann::json::object();
};

struct Node {
    std::string name;
    int parent = -1;
    std::vector<int> children;
    glm::vec3 translation{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  ///< w, x, y, z
    glm::vec3 scale{1.0f};
    int mesh = -1;
    int light = -1;
    int camera = -1;
    /// Index into Scene::skins: the node's mesh is deformed by that skin's joints, and, as the
    /// glTF specification says, placed by them alone (this node's own transform is ignored
    /// for the mesh; its children still use it).
    int skin = -1;
    NodeFlags flags;

    [[nodiscard]] glm::mat4 local_matrix() const;
};

/// Counts of what loading dropped or repaired, reported to the user.
struct LoadReport {
    std::size_t degenerate_triangles_dropped = 0;
    std::size_t primitives_skipped = 0;  ///< non-triangle modes
    std::vector<std::string> warnings;
    /// The files besides the glTF itself that the load read (buffers, images), by real path:
    /// what a tool must not overwrite.
    std::vector<std::filesystem::path> external_files;
};

struct Scene {
    std::string name;
    std::vector<Node> nodes;
    std::vector<int> roots;  ///< nodes of the default scene without a parent
    std::vector<Mesh> meshes;
    std::vector<Material> materials;
    std::vector<Image> images;
    std::vector<Light> lights;
    std::vector<Camera> cameras;
    std::vector<Animation> animations;
    std::vector<Skin> skins;
    /// The level's sky, from the glTF scene's extras.luxel.sky (None without one).
    SkySpec sky;
    LoadReport report;
    /// The file the scene was loaded from, as the loader names it in its errors; empty for a
    /// scene built in code. Errors found after loading (an image that does not decode, a
    /// light-map table the instance rejects) name it through in_file().
    std::string source;

    /// "SOURCE: what" (just `what` without a source): a message naming the level file.
    [[nodiscard]] std::string in_file(const std::string& what) const {
        return source.empty() ? what : source + ": " + what;
    }

    /// Every node index once, each after its parent. Throws luxel::Error on a cycle.
    [[nodiscard]] std::vector<std::size_t> parent_first_order() const;
    /// Local-to-world matrices for every node in the rest pose (no animation applied).
    [[nodiscard]] std::vector<glm::mat4> world_matrices() const;
    /// True when the node has an explicit dynamic flag set, or (without one) when an animation
    /// targets it or one of its ancestors, or an ancestor is flagged dynamic (whatever moves
    /// an ancestor moves the node). A node with a skin is always dynamic: its mesh deforms
    /// with its joints, so it gets no light map whatever its flag says. So is a mesh node with
    /// extras.luxel.wave: its vertices move every frame (world/vertex_wave.hpp).
    [[nodiscard]] bool is_dynamic(int node) const;
    [[nodiscard]] std::size_t triangle_count() const;
    /// Checks every index and size invariant stated in this header; throws luxel::Error
    /// naming the first violation. Loaders and writers call it.
    void validate() const;
};

}  // namespace luxel::scene
