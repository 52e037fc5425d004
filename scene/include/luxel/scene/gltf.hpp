#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "luxel/scene/scene.hpp"

/// glTF 2.0 in and out. Loading checks every index, size and number in the file before it is
/// used, so a hostile or broken file ends in a luxel::Error naming the file and the problem,
/// never in a crash, a hang or an allocation the file's size does not justify.
namespace luxel::scene {

/// Upper bounds a loaded file must respect. The defaults are far above any real level; they
/// exist so that no count in a file can make the loader allocate without bound. Each is checked
/// before anything is allocated for what it counts, and counted the way it costs. Every one can
/// be raised on the tools' command line, `--limit NAME=N` (load_limits() lists the names;
/// docs/LEVELS.md has the table).
struct LoadOptions {
    std::uint64_t max_file_size = std::uint64_t{1}
                                  << 30;  ///< the .gltf/.glb, and each file it names
    /// Everything read from external files (buffers, images) together.
    std::uint64_t max_external_bytes = std::uint64_t{4} << 30;
    std::uint64_t max_accessor_elements = std::uint64_t{1} << 28;
    std::uint64_t max_total_triangles = std::uint64_t{1} << 27;
    /// Triangles counted once per node that draws them: what the ray scene and luxel-prep's
    /// per-node copies hold.
    std::uint64_t max_instanced_triangles = std::uint64_t{1} << 24;
    /// The same count for luxel-prep, which welds, charts and writes a copy of every
    /// triangle per node in half-edge form (about 500 bytes a triangle at its peak): checked
    /// before the copies are made.
    std::uint64_t max_prep_triangles = std::uint64_t{1} << 22;
    /// Light-map texels over every page the layouts name. The real-time maps with their GL
    /// textures take about 210 bytes a texel in luxel-sandbox (one 4096^2 page, 16M texels:
    /// 3.5 GB resident on llvmpipe), so the default, 8M, keeps them near 1.7 GB.
    std::uint64_t max_lightmap_texels = std::uint64_t{1} << 23;
    /// Bytes the reference integrator (luxel-ref, luxel-bench's reference) keeps for every
    /// light-map texel together: its per-texel state is several times the real-time maps', so
    /// a level within lightmap-texels can still need more memory than the machine has. Checked
    /// after the maps are laid out, before the reference allocates anything per texel.
    std::uint64_t max_reference_bytes = std::uint64_t{2} << 30;
    /// Pixels of every image together, read from their headers (each decodes to 4 bytes).
    std::uint64_t max_image_pixels = std::uint64_t{1} << 28;
    std::uint64_t max_nodes = std::uint64_t{1} << 20;
    /// Elements of any other top-level array (meshes, materials, accessors, ...): counted while
    /// the JSON is first read, before anything is allocated for them.
    std::uint64_t max_array_elements = std::uint64_t{1} << 20;
    /// KHR_lights_punctual lights: each costs photons and, drawn, a shadow map.
    std::uint64_t max_lights = 16384;
    /// Nodes that place a light: what the world holds and emits photons from, however
    /// few lights they share (50,000 nodes naming one light are 50,000 lights).
    std::uint64_t max_light_instances = 16384;
    /// Placed lights the renderer gives a shadow map: every punctual light (point and wide
    /// spot lights a cube of six 512^2 depth faces, 6 MiB; spot and directional a 1024^2 map,
    /// 4 MiB). 256 cube maps are 1.5 GiB of GL memory.
    std::uint64_t max_shadowed_lights = 256;
    std::uint64_t max_node_depth = 1024;
    /// JSON nesting (arrays and objects inside each other); glTF itself needs about 8.
    std::uint64_t max_json_depth = 256;
};

/// One of LoadOptions' limits, by the name the command line knows it by.
struct LoadLimit {
    const char* name;                   ///< `--limit NAME=N`
    std::uint64_t LoadOptions::*value;  ///< the member it sets
    const char* counts;                 ///< what it counts (as docs/LEVELS.md's table says)
};

/// Every limit of LoadOptions, in the order docs/LEVELS.md lists them.
[[nodiscard]] std::span<const LoadLimit> load_limits();

/// Applies "NAME=N" (N a whole number, with an optional k, M or G suffix for 2^10, 2^20,
/// 2^30) to `options`. Throws luxel::Error naming the known limits for an unknown name or a
/// bad number.
void set_load_limit(LoadOptions& options, const std::string& assignment);

/// Loads a .gltf or .glb (told apart by the GLB magic, not the extension). External buffers
/// and images are read only from the file's directory and below. Throws luxel::Error whose
/// message starts with the file's path.
[[nodiscard]] Scene load_gltf(const std::filesystem::path& file, const LoadOptions& options = {});

/// Loads glTF from memory (.glb when the bytes start with the GLB magic, JSON otherwise).
/// `display_name` starts every error message. External files are resolved inside `base_dir`;
/// with an empty `base_dir` a file that names an external file is an error.
[[nodiscard]] Scene load_gltf_from_memory(std::span<const std::uint8_t> bytes,
                                          const std::string& display_name,
                                          const std::filesystem::path& base_dir = {},
                                          const LoadOptions& options = {});

struct SaveOptions {
    /// For .gltf: put the binary buffer into the JSON as a base64 data URI instead of writing
    /// `<stem>.bin` beside the file. Ignored for .glb (always one self-contained file).
    bool embed_buffers = false;
};

/// Writes the scene as .glb (one binary buffer, images embedded) or .gltf (JSON plus
/// `<stem>.bin`, or embedded base64 with SaveOptions::embed_buffers), chosen by the file's
/// extension. The output passes the Khronos glTF validator without errors. Calls
/// Scene::validate() first; throws luxel::Error naming the file when it cannot write.
void save_gltf(const Scene& scene, const std::filesystem::path& file,
               const SaveOptions& options = {});

enum class GltfContainer {
    Binary,        ///< .glb
    EmbeddedText,  ///< .gltf with the buffer as a base64 data URI
};

/// The bytes save_gltf would write for a self-contained file (tests, fuzzing seeds).
[[nodiscard]] std::vector<std::uint8_t> save_gltf_to_memory(const Scene& scene,
                                                            GltfContainer container);

}  // namespace luxel::scene
