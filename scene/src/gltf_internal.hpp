#pragma once

// Shared between the glTF loader's and writer's source files; not part of the public API.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/ext/vector_uint4_sized.hpp>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "luxel/scene/gltf.hpp"

namespace tinygltf {
class Model;
}

namespace luxel::scene::gltf_detail {

/// Everything one load shares: the parsed model, where errors and warnings go, the limits.
class ImportContext {
  public:
    ImportContext(const tinygltf::Model& model, const std::string& display_name,
                  const LoadOptions& options, Scene& scene)
        : model_(model), display_name_(display_name), options_(options), scene_(scene) {}

    [[nodiscard]] const tinygltf::Model& model() const { return model_; }
    [[nodiscard]] const LoadOptions& options() const { return options_; }
    [[nodiscard]] Scene& scene() const { return scene_; }

    /// Throws luxel::Error("<file>: <problem>").
    [[noreturn]] void fail(const std::string& problem) const;
    /// Records a warning in the scene's LoadReport (and the log).
    void warn(const std::string& message) const;

    /// Adds a primitive's triangles to the running total; fails past the limit, before the
    /// primitive's data is read.
    void count_triangles(std::uint64_t triangles, const std::string& where);

    /// Index of the Scene image for glTF image `gltf_image`, importing it on first use.
    int scene_image(int gltf_image, const std::string& where);

  private:
    const tinygltf::Model& model_;
    const std::string& display_name_;
    const LoadOptions& options_;
    Scene& scene_;
    std::uint64_t triangles_ = 0;
    std::vector<int> image_map_;
};

/// "mesh 3 'Floor'" style labels for messages.
[[nodiscard]] std::string label(const char* kind, std::size_t index, const std::string& name);

/// Parses a JSON string tinygltf kept for `extras`/`extensions` (empty: an empty object).
[[nodiscard]] nlohmann::json parse_kept_json(const std::string& text);

// --- accessors (gltf_accessors.cpp) ---------------------------------------------------------

/// Reads accessor `index` as floats, `components` per element (a glTF type of that many
/// components), accepting float and, where `allow_normalized`, the normalized integer types
/// glTF permits for that use. Checks range, type, count limit, buffer bounds (overflow-safe,
/// before anything is read or allocated) and that every value is finite.
[[nodiscard]] std::vector<float> read_floats(const ImportContext& context, int index,
                                             int components, bool allow_normalized,
                                             const std::string& usage);
/// Reads a SCALAR unsigned byte/short/int accessor (primitive indices).
[[nodiscard]] std::vector<std::uint32_t> read_indices(const ImportContext& context, int index,
                                                      const std::string& usage);
/// Reads a VEC4 unsigned byte/short accessor (JOINTS_0), with the same checks.
[[nodiscard]] std::vector<glm::u16vec4> read_joints(const ImportContext& context, int index,
                                                    const std::string& usage);
/// The element count of accessor `index` after checking it exists and respects the limit.
[[nodiscard]] std::uint64_t accessor_count(const ImportContext& context, int index,
                                           const std::string& usage);

// --- the parts of the scene (gltf_import_*.cpp) ----------------------------------------------

void import_materials(ImportContext& context);
/// The limits on how the parts combine (gltf_import_limits.cpp): instanced triangles, light-map
/// texels over all pages, decoded image pixels. Run after import_nodes.
void check_combined_limits(const ImportContext& context);
void import_meshes(ImportContext& context);
void import_lights(ImportContext& context);
void import_cameras(ImportContext& context);
void import_nodes(ImportContext& context);
void import_animations(ImportContext& context);
/// Skins (gltf_import_skins.cpp): joints and inverse bind matrices. Run after import_nodes.
void import_skins(ImportContext& context);

// --- containers (gltf_container.cpp) ---------------------------------------------------------

inline constexpr std::uint32_t kGlbMagic = 0x46546C67;      // "glTF"
inline constexpr std::uint32_t kGlbJsonChunk = 0x4E4F534A;  // "JSON"
inline constexpr std::uint32_t kGlbBinChunk = 0x004E4942;   // "BIN\0"

[[nodiscard]] bool has_glb_magic(std::span<const std::uint8_t> bytes);

struct GlbLayout {
    std::span<const std::uint8_t> json;
    std::span<const std::uint8_t> bin;  ///< empty when the file has no BIN chunk
    std::uint32_t declared_length = 0;  ///< the header's total length (== bytes.size())
};

/// Checks the GLB header and chunk table completely (lengths, alignment, order, bounds);
/// returns a description of the first problem in `problem` and an empty layout when invalid.
[[nodiscard]] GlbLayout parse_glb(std::span<const std::uint8_t> bytes, std::string& problem);

/// Checks, in one streaming pass without building a document (gltf_json_check.cpp), that
/// `text` is JSON nested within the limit, that its top-level arrays and its lights are within
/// their limits, and that every index and count the glTF schema declares is a whole number
/// >= 0. Returns an empty string or the problem.
[[nodiscard]] std::string check_json(std::span<const std::uint8_t> text, const LoadOptions& limits);

/// Assembles a GLB from its JSON text and binary buffer (padding both chunks).
[[nodiscard]] std::vector<std::uint8_t> build_glb(const std::string& json,
                                                  std::span<const std::uint8_t> bin);

[[nodiscard]] std::string base64_encode(std::span<const std::uint8_t> bytes);

// --- writing (gltf_writer.cpp) ---------------------------------------------------------------

struct EncodedGltf {
    nlohmann::json document;        ///< buffers[0] has byteLength but no uri yet
    std::vector<std::uint8_t> bin;  ///< the single binary buffer (may be empty)
};

/// Turns a validated scene into a glTF document and its binary buffer.
[[nodiscard]] EncodedGltf encode_scene(const Scene& scene);

}  // namespace luxel::scene::gltf_detail
