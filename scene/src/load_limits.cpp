// LoadOptions' limits by name: the one table --limit NAME=N, --help and docs/LEVELS.md follow.

#include <array>
#include <charconv>

#include "luxel/runtime/error.hpp"
#include "luxel/scene/gltf.hpp"

namespace luxel::scene {
namespace {

constexpr std::array kLimits = {
    LoadLimit{"file-bytes", &LoadOptions::max_file_size,
              "bytes of the .gltf/.glb and of each file it names"},
    LoadLimit{"external-bytes", &LoadOptions::max_external_bytes,
              "bytes of every external buffer and image together"},
    LoadLimit{"json-depth", &LoadOptions::max_json_depth, "nesting of JSON arrays and objects"},
    LoadLimit{"nodes", &LoadOptions::max_nodes, "nodes"},
    LoadLimit{"elements", &LoadOptions::max_array_elements,
              "elements of any other top-level array (meshes, materials, accessors, ...)"},
    LoadLimit{"lights", &LoadOptions::max_lights, "KHR_lights_punctual lights"},
    LoadLimit{"light-instances", &LoadOptions::max_light_instances,
              "nodes that place a light, each counted"},
    LoadLimit{"shadowed-lights", &LoadOptions::max_shadowed_lights,
              "placed lights that get a shadow map when drawn"},
    LoadLimit{"node-depth", &LoadOptions::max_node_depth, "levels of the node hierarchy"},
    LoadLimit{"accessor-elements", &LoadOptions::max_accessor_elements, "elements of one accessor"},
    LoadLimit{"triangles", &LoadOptions::max_total_triangles,
              "triangles of every mesh, each mesh once"},
    LoadLimit{"instanced-triangles", &LoadOptions::max_instanced_triangles,
              "triangles counted once per node that draws them"},
    LoadLimit{"prep-triangles", &LoadOptions::max_prep_triangles,
              "triangles luxel-prep copies, once per node that draws them"},
    LoadLimit{"lightmap-texels", &LoadOptions::max_lightmap_texels,
              "light-map texels over every page the layouts name"},
    LoadLimit{"reference-bytes", &LoadOptions::max_reference_bytes,
              "bytes of the reference integrator's per-texel state over every light-mapped texel"},
    LoadLimit{"image-pixels", &LoadOptions::max_image_pixels,
              "pixels of every image together, read from their headers"},
};

std::string known_names() {
    std::string names;
    for (const LoadLimit& limit : kLimits) {
        names += (names.empty() ? "" : ", ") + std::string(limit.name);
    }
    return names;
}

}  // namespace

std::span<const LoadLimit> load_limits() {
    return kLimits;
}

void set_load_limit(LoadOptions& options, const std::string& assignment) {
    const auto equals = assignment.find('=');
    const std::string name = assignment.substr(0, equals);
    const LoadLimit* found = nullptr;
    for (const LoadLimit& limit : load_limits()) {
        if (name == limit.name) {
            found = &limit;
        }
    }
    if (found == nullptr || equals == std::string::npos) {
        throw Error("--limit " + assignment + ": expected NAME=N with NAME one of " +
                    known_names());
    }
    std::string digits = assignment.substr(equals + 1);
    int shift = 0;
    if (!digits.empty()) {
        switch (digits.back()) {
            case 'k':
                shift = 10;
                break;
            case 'M':
                shift = 20;
                break;
            case 'G':
                shift = 30;
                break;
            default:
                break;
        }
        if (shift != 0) {
            digits.pop_back();
        }
    }
    std::uint64_t value = 0;
    const auto* end = digits.data() + digits.size();
    const auto result = std::from_chars(digits.data(), end, value);
    if (digits.empty() || result.ec != std::errc() || result.ptr != end ||
        (shift != 0 && value > (~std::uint64_t{0} >> shift))) {
        throw Error("--limit " + assignment + ": '" + assignment.substr(equals + 1) +
                    "' is not a whole number (k, M or G may follow)");
    }
    options.*(found->value) = value << shift;
}

}  // namespace luxel::scene
