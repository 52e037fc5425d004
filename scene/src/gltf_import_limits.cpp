// The limits that depend on how the parts of a scene combine, checked once the nodes are read
// and before anything downstream allocates for them: triangles counted per instance (a mesh
// drawn by 2,000 nodes costs 2,000 times), light-map texels over every page the layouts name,
// and the pixels every image will decode to. Each is a small count in a small file that would
// otherwise become gigabytes in luxel-prep, the ray scene or the light maps.

#include <algorithm>
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "gltf_internal.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/scene/image_decode.hpp"
#include "luxel/scene/lightmap_layout.hpp"

namespace luxel::scene::gltf_detail {
namespace {

void check_instanced_triangles(const ImportContext& context) {
    const Scene& scene = context.scene();
    const std::uint64_t limit = context.options().max_instanced_triangles;
    std::vector<std::uint64_t> mesh_triangles;
    mesh_triangles.reserve(scene.meshes.size());
    for (const Mesh& mesh : scene.meshes) {
        std::uint64_t triangles = 0;
        for (const Primitive& primitive : mesh.primitives) {
            triangles += primitive.triangle_count();
        }
        mesh_triangles.push_back(triangles);
    }
    std::uint64_t total = 0;
    for (const Node& node : scene.nodes) {
        if (node.mesh >= 0) {
            total += mesh_triangles[static_cast<std::size_t>(node.mesh)];
        }
        if (total > limit) {
            context.fail("the nodes draw more than " + std::to_string(limit) +
                         " triangles in all, counting each instance of a mesh (the limit on "
                         "instanced triangles)");
        }
    }
}

void check_lightmap_texels(const ImportContext& context) {
    const Scene& scene = context.scene();
    std::optional<int> page_size;
    // 64 bits: a page index may be INT_MAX, and the count is one more.
    std::int64_t pages = 0;
    for (std::size_t i = 0; i < scene.nodes.size(); ++i) {
        const Node& node = scene.nodes[i];
        const std::string where = label("node", i, node.name);
        std::optional<LightmapLayout> layout;
        try {
            layout = read_lightmap_layout(node.flags.raw);
        } catch (const Error& e) {
            context.fail(where + ": " + e.what());
        }
        if (!layout) {
            continue;
        }
        if (layout->page_size > kMaxLightmapPageSize) {
            context.fail(where + ": light-map pages of " + std::to_string(layout->page_size) +
                         " texels exceed the largest luxel-prep writes (" +
                         std::to_string(kMaxLightmapPageSize) + ")");
        }
        if (page_size && *page_size != layout->page_size) {
            context.fail(where + ": light-map page size " + std::to_string(layout->page_size) +
                         " differs from the other nodes' " + std::to_string(*page_size));
        }
        page_size = layout->page_size;
        for (const LightmapSurface& surface : layout->surfaces) {
            pages = std::max(pages, std::int64_t{surface.page} + 1);
        }
    }
    if (!page_size) {
        return;
    }
    const std::uint64_t texels = static_cast<std::uint64_t>(pages) *
                                 static_cast<std::uint64_t>(*page_size) *
                                 static_cast<std::uint64_t>(*page_size);
    if (texels > context.options().max_lightmap_texels) {
        context.fail("the light-map layout names " + std::to_string(pages) + " pages of " +
                     std::to_string(*page_size) + "^2 texels, " + std::to_string(texels) +
                     " texels in all, more than the limit of " +
                     std::to_string(context.options().max_lightmap_texels));
    }
}

void check_image_pixels(const ImportContext& context) {
    const Scene& scene = context.scene();
    const std::uint64_t limit = context.options().max_image_pixels;
    std::uint64_t total = 0;
    for (std::size_t i = 0; i < scene.images.size(); ++i) {
        const ImageSize size = [&] {
            try {
                return read_image_size(scene.images[i], static_cast<int>(i));
            } catch (const Error& e) {
                context.fail(e.what());
            }
        }();
        total += static_cast<std::uint64_t>(size.width) * static_cast<std::uint64_t>(size.height);
        if (total > limit) {
            context.fail("the images decode to more than " + std::to_string(limit) +
                         " pixels in all (the limit on image pixels; " +
                         image_label(scene.images[i], static_cast<int>(i)) + " is " +
                         std::to_string(size.width) + "x" + std::to_string(size.height) + ")");
        }
    }
}

/// Counted per node, before the world makes an entity, photons or a shadow map for any: one
/// light named by 50,000 nodes is 50,000 lights.
void check_light_instances(const ImportContext& context) {
    const Scene& scene = context.scene();
    std::uint64_t placed = 0;
    for (const Node& node : scene.nodes) {
        placed += node.light >= 0 ? 1 : 0;
    }
    const std::uint64_t instances = context.options().max_light_instances;
    if (placed > instances) {
        context.fail(std::to_string(placed) + " nodes place a light, more than the limit of " +
                     std::to_string(instances) + " (light-instances)");
    }
    // The renderer gives every placed punctual light a shadow map (frame_lights.cpp): a cube
    // map for point lights and wide spots, a 2D map for the others.
    const std::uint64_t shadowed = context.options().max_shadowed_lights;
    if (placed > shadowed) {
        context.fail(std::to_string(placed) +
                     " placed lights would each get a shadow map when drawn, more than the "
                     "limit of " +
                     std::to_string(shadowed) + " (shadowed-lights)");
    }
}

}  // namespace

void check_combined_limits(const ImportContext& context) {
    check_light_instances(context);
    check_instanced_triangles(context);
    check_lightmap_texels(context);
    check_image_pixels(context);
}

}  // namespace luxel::scene::gltf_detail
