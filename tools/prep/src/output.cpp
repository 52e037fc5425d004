#include "luxel/prep/output.hpp"

#include <algorithm>
#include <unordered_map>

namespace luxel::prep {
namespace {

/// Identifies one output vertex of a surface primitive: a source vertex (which brings its own
/// normal and TEXCOORD_0) in one chart (which brings TEXCOORD_1). Source vertices welded into
/// one mesh vertex stay apart where their other attributes differ; one source vertex on a chart
/// seam becomes one vertex per chart.
struct VertexKey {
    int chart_vertex;  ///< surface-wide index: chart offset + chart vertex
    int primitive;
    std::uint32_t vertex;
    friend bool operator==(const VertexKey&, const VertexKey&) = default;
};

struct VertexKeyHash {
    std::size_t operator()(const VertexKey& key) const {
        const auto mix = static_cast<std::uint64_t>(key.chart_vertex) * 0x9E3779B97F4A7C15ull ^
                         static_cast<std::uint64_t>(key.primitive) * 0xC2B2AE3D27D4EB4Full ^
                         static_cast<std::uint64_t>(key.vertex) * 0x165667B19E3779F9ull;
        return static_cast<std::size_t>(mix ^ (mix >> 31));
    }
};

glm::vec3 normal_to_local(const glm::dvec3& world_normal, const glm::dmat3& linear,
                          const glm::dvec3& fallback) {
    // Normals transform with the inverse transpose; back to local space that is the transpose.
    glm::dvec3 n = glm::transpose(linear) * world_normal;
    const double length = glm::length(n);
    if (!(length > 1e-12)) {
        n = fallback;
    } else {
        n /= length;
    }
    return glm::vec3(n);
}

/// One surface as a primitive of the node's mesh.
scene::Primitive surface_primitive(const scene::Mesh& source, const PreparedNode& node,
                                   const PreparedSurface& surface) {
    const NodeGeometry& geometry = node.geometry;
    scene::Primitive primitive;
    primitive.material = surface.material;
    bool any_texcoords = false;
    bool any_missing_normals = false;
    for (const int c : surface.charts) {
        for (const int f : node.charts[static_cast<std::size_t>(c)].faces) {
            for (const SourceCorner& corner : geometry.faces[static_cast<std::size_t>(f)].source) {
                const scene::Primitive& p =
                    source.primitives[static_cast<std::size_t>(corner.primitive)];
                any_texcoords = any_texcoords || !p.texcoords0.empty();
                any_missing_normals = any_missing_normals || p.normals.empty();
            }
        }
    }
    // Smooth normals for corners whose primitive has none: area-weighted face normals around
    // each mesh vertex, over this surface only, so creases between surfaces stay sharp.
    std::unordered_map<int, glm::dvec3> smooth;
    if (any_missing_normals) {
        for (const int c : surface.charts) {
            for (const int f : node.charts[static_cast<std::size_t>(c)].faces) {
                const Face& face = geometry.faces[static_cast<std::size_t>(f)];
                for (const int v : face.vertices) {
                    smooth[v] += face.area * face.normal;
                }
            }
        }
    }
    const glm::dmat3 linear(geometry.world);
    std::unordered_map<VertexKey, std::uint32_t, VertexKeyHash> output_vertex;
    int chart_offset = 0;
    for (const int c : surface.charts) {
        const Chart& chart = node.charts[static_cast<std::size_t>(c)];
        const PlacedChart& placed = node.placed[static_cast<std::size_t>(c)];
        for (std::size_t i = 0; i < chart.faces.size(); ++i) {
            const Face& face = geometry.faces[static_cast<std::size_t>(chart.faces[i])];
            for (std::size_t k = 0; k < 3; ++k) {
                const SourceCorner& corner = face.source[k];
                const int chart_vertex = chart.corners[i][k];
                const VertexKey key{chart_offset + chart_vertex, corner.primitive, corner.vertex};
                const auto [entry, inserted] = output_vertex.emplace(
                    key, static_cast<std::uint32_t>(primitive.positions.size()));
                if (inserted) {
                    const scene::Primitive& from =
                        source.primitives[static_cast<std::size_t>(corner.primitive)];
                    primitive.positions.push_back(from.positions[corner.vertex]);
                    if (!from.normals.empty()) {
                        primitive.normals.push_back(from.normals[corner.vertex]);
                    } else {
                        const glm::dvec3 local_face = glm::transpose(linear) * face.normal;
                        primitive.normals.push_back(normal_to_local(
                            smooth[face.vertices[k]], linear,
                            glm::length(local_face) > 0.0 ? glm::normalize(local_face)
                                                          : glm::dvec3(0.0, 1.0, 0.0)));
                    }
                    if (any_texcoords) {
                        primitive.texcoords0.push_back(from.texcoords0.empty()
                                                           ? glm::vec2(0.0f)
                                                           : from.texcoords0[corner.vertex]);
                    }
                    primitive.texcoords1.push_back(
                        placed.page_uv[static_cast<std::size_t>(chart_vertex)]);
                }
                primitive.indices.push_back(entry->second);
            }
        }
        chart_offset += static_cast<int>(chart.vertices.size());
    }
    return primitive;
}

}  // namespace

PlacedChart place_chart(const Chart& chart, const ChartPlacement& placement, int page_size) {
    PlacedChart placed;
    placed.page = placement.page;
    const int w = placement.rotated ? chart.height : chart.width;
    const int h = placement.rotated ? chart.width : chart.height;
    placed.rect = {placement.x, placement.y, w, h};
    const double size = page_size;
    std::vector<glm::dvec2> stored(chart.uv.size());
    placed.page_uv.resize(chart.uv.size());
    for (std::size_t v = 0; v < chart.uv.size(); ++v) {
        const glm::dvec2 local = placement.rotated
                                     ? glm::dvec2(chart.height - chart.uv[v].y, chart.uv[v].x)
                                     : chart.uv[v];
        const glm::dvec2 texel = local + glm::dvec2(placement.x, placement.y);
        placed.page_uv[v] = glm::vec2(texel / size);
        // Back from the float that is stored, relative to the rectangle.
        stored[v] = glm::dvec2(placed.page_uv[v]) * size - glm::dvec2(placement.x, placement.y);
    }
    placed.mask = cover(stored, chart.corners, w, h);
    placed.texels = placed.mask.count();
    return placed;
}

scene::Scene build_output_scene(const scene::Scene& input, const std::vector<PreparedNode>& nodes,
                                int page_size, std::vector<std::string>& warnings) {
    scene::Scene output = input;
    // Stale light-map UVs on meshes that get no light map would be mistaken for one.
    for (auto& mesh : output.meshes) {
        for (auto& primitive : mesh.primitives) {
            primitive.texcoords1.clear();
        }
    }
    for (auto& node : output.nodes) {
        node.flags.raw.erase("lightmap");
    }
    std::vector<bool> mesh_taken(input.meshes.size(), false);
    // A skinned node keeps its mesh as it came (joints and weights): a light-mapped node
    // sharing that mesh gets a copy instead of rewriting it.
    for (const scene::Node& node : input.nodes) {
        if (node.skin >= 0 && node.mesh >= 0) {
            mesh_taken[static_cast<std::size_t>(node.mesh)] = true;
        }
    }
    for (const PreparedNode& prepared : nodes) {
        scene::Node& node = output.nodes[static_cast<std::size_t>(prepared.node)];
        const scene::Mesh& source = input.meshes[static_cast<std::size_t>(node.mesh)];
        scene::Mesh mesh;
        mesh.name = source.name;
        scene::LightmapLayout layout;
        layout.texel_size = static_cast<float>(prepared.texel_size);
        layout.page_size = page_size;
        for (const PreparedSurface& surface : prepared.surfaces) {
            scene::LightmapSurface entry;
            entry.id = surface.id;
            entry.primitive = static_cast<int>(mesh.primitives.size());
            entry.page = surface.page;
            entry.rect = surface.rect;
            for (const int c : surface.charts) {
                entry.charts.push_back(prepared.placed[static_cast<std::size_t>(c)].rect);
            }
            entry.area = surface.area;
            entry.texels = surface.texels;
            entry.texel_size = surface.texel_size;
            layout.surfaces.push_back(std::move(entry));
            mesh.primitives.push_back(surface_primitive(source, prepared, surface));
        }
        for (std::size_t p = 0; p < source.primitives.size(); ++p) {
            if (!prepared.geometry.primitive_lightmapped[p]) {
                mesh.primitives.push_back(source.primitives[p]);
                mesh.primitives.back().texcoords1.clear();
            }
        }
        const auto index = static_cast<std::size_t>(node.mesh);
        if (!mesh_taken[index]) {
            mesh_taken[index] = true;
            output.meshes[index] = std::move(mesh);
        } else {
            node.mesh = static_cast<int>(output.meshes.size());
            output.meshes.push_back(std::move(mesh));
        }
        node.flags.raw["lightmap"] = scene::to_json(layout);
    }
    if (nodes.empty() && !input.meshes.empty()) {
        warnings.emplace_back("no mesh node has a light-mapped surface; the scene is unchanged");
    }
    return output;
}

}  // namespace luxel::prep
