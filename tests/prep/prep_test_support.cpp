#include "prep_test_support.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <sstream>

#include "luxel/prep/raster.hpp"
#include "luxel/runtime/jobs.hpp"
#include "luxel/scene/lightmap_layout.hpp"
#include "test_paths.hpp"

namespace luxel::testing {
namespace {

/// Area of a triangle clipped to the texel square [x, x+1] x [y, y+1] (Sutherland-Hodgman).
double overlap_area(const std::array<glm::dvec2, 3>& triangle, int x, int y) {
    std::vector<glm::dvec2> polygon(triangle.begin(), triangle.end());
    // Keep the side where inside(p) >= 0 of each of the square's four edges.
    const std::array<std::pair<int, double>, 4> planes{
        {{0, static_cast<double>(x)}, {1, static_cast<double>(y)}, {2, x + 1.0}, {3, y + 1.0}}};
    for (const auto& [kind, value] : planes) {
        auto inside = [kind = kind, value = value](const glm::dvec2& p) {
            switch (kind) {
                case 0:
                    return p.x - value;
                case 1:
                    return p.y - value;
                case 2:
                    return value - p.x;
                default:
                    return value - p.y;
            }
        };
        std::vector<glm::dvec2> clipped;
        for (std::size_t i = 0; i < polygon.size(); ++i) {
            const glm::dvec2 a = polygon[i];
            const glm::dvec2 b = polygon[(i + 1) % polygon.size()];
            const double da = inside(a);
            const double db = inside(b);
            if (da >= 0.0) {
                clipped.push_back(a);
            }
            if ((da >= 0.0) != (db >= 0.0)) {
                clipped.push_back(a + (b - a) * (da / (da - db)));
            }
        }
        polygon = std::move(clipped);
        if (polygon.empty()) {
            return 0.0;
        }
    }
    double twice = 0.0;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const glm::dvec2 a = polygon[i];
        const glm::dvec2 b = polygon[(i + 1) % polygon.size()];
        twice += a.x * b.y - a.y * b.x;
    }
    return std::abs(0.5 * twice);
}

/// True when two triangles share UV space: samples on a fine grid strictly inside more than
/// one triangle (by barycentric coordinates, so shared edges never count).
bool folds_over(const std::vector<glm::dvec2>& uv, const std::vector<std::array<int, 3>>& triangles,
                int width, int height) {
    constexpr int kSamples = 4;
    const int columns = width * kSamples;
    const int rows = height * kSamples;
    std::vector<std::uint8_t> hits(
        static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows), 0);
    for (const auto& triangle : triangles) {
        const glm::dvec2 a = uv[static_cast<std::size_t>(triangle[0])];
        const glm::dvec2 b = uv[static_cast<std::size_t>(triangle[1])];
        const glm::dvec2 c = uv[static_cast<std::size_t>(triangle[2])];
        const double twice = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
        if (!(twice > 0.0)) {
            continue;
        }
        const glm::dvec2 low = glm::min(a, glm::min(b, c)) * static_cast<double>(kSamples);
        const glm::dvec2 high = glm::max(a, glm::max(b, c)) * static_cast<double>(kSamples);
        for (int j = std::max(0, static_cast<int>(low.y));
             j < std::min(static_cast<int>(high.y) + 1, rows); ++j) {
            for (int i = std::max(0, static_cast<int>(low.x));
                 i < std::min(static_cast<int>(high.x) + 1, columns); ++i) {
                const glm::dvec2 s((i + 0.5) / kSamples, (j + 0.5) / kSamples);
                const double w0 = ((b.x - s.x) * (c.y - s.y) - (b.y - s.y) * (c.x - s.x)) / twice;
                const double w1 = ((c.x - s.x) * (a.y - s.y) - (c.y - s.y) * (a.x - s.x)) / twice;
                const double w2 = 1.0 - w0 - w1;
                if (w0 > 1e-6 && w1 > 1e-6 && w2 > 1e-6 &&
                    ++hits[static_cast<std::size_t>(j) * static_cast<std::size_t>(columns) +
                           static_cast<std::size_t>(i)] > 1) {
                    return true;
                }
            }
        }
    }
    return false;
}

void fail(PageCheck& check, const std::string& message) {
    if (check.failures.size() < 20) {
        check.failures.push_back(message);
    }
}

}  // namespace

std::vector<std::string> built_in_level_names() {
    return {"cornell",  "cornell-13k", "cornell-133k", "two-rooms",
            "caustics", "sandbox",     "sky-room",     "furnace"};
}

std::vector<std::string> blender_level_names() {
    return {"crate-footprint", "sky-window", "tinted-glass", "skinned-figure"};
}

std::filesystem::path level_file(const std::string& name) {
    const std::vector<std::string> blender = blender_level_names();
    if (std::find(blender.begin(), blender.end(), name) != blender.end()) {
        return luxel::testing::source_dir() / "tests" / "levels" / "blender" / (name + ".glb");
    }
    return luxel::testing::source_dir() / "assets" / "levels" / (name + ".glb");
}

std::filesystem::path prepared_level_file(const std::string& name) {
    return luxel::testing::source_dir() / "assets" / "levels" / "prepared" / (name + ".glb");
}

scene::Material diffuse_material(const std::string& name) {
    scene::Material material;
    material.name = name;
    material.metallic = 0.0f;
    material.roughness = 1.0f;
    material.base_color = glm::vec4(0.7f, 0.7f, 0.7f, 1.0f);
    return material;
}

scene::Scene single_mesh_scene(scene::Primitive primitive, const std::string& name) {
    scene::Scene s;
    s.materials.push_back(diffuse_material());
    primitive.material = 0;
    scene::Mesh mesh;
    mesh.name = name;
    mesh.primitives.push_back(std::move(primitive));
    s.meshes.push_back(std::move(mesh));
    scene::Node node;
    node.name = name;
    node.mesh = 0;
    s.nodes.push_back(node);
    s.roots.push_back(0);
    return s;
}

int add_mesh_node(scene::Scene& scene, const std::string& name, scene::Primitive primitive,
                  const glm::vec3& translation) {
    scene.meshes.push_back({name, {std::move(primitive)}});
    scene::Node node;
    node.name = name;
    node.mesh = static_cast<int>(scene.meshes.size() - 1);
    node.translation = translation;
    scene.nodes.push_back(node);
    const int index = static_cast<int>(scene.nodes.size() - 1);
    scene.roots.push_back(index);
    return index;
}

prep::PrepResult run_prep(const scene::Scene& scene, const prep::PrepOptions& options,
                          int threads) {
    JobSystem jobs(threads);
    return prep::prepare(scene, options, jobs);
}

PageCheck check_light_map_pages(const scene::Scene& prepared, int padding, double max_stretch) {
    PageCheck check;
    const auto world = prepared.world_matrices();
    // page -> owner chart of each texel (-1 free), created when a page is first seen.
    std::map<int, std::vector<int>> claims;
    int page_size = 0;
    int chart_counter = 0;
    for (std::size_t n = 0; n < prepared.nodes.size(); ++n) {
        const scene::Node& node = prepared.nodes[n];
        const auto layout = scene::read_lightmap_layout(node.flags.raw);
        if (!layout) {
            continue;
        }
        const std::string where = "node '" + node.name + "'";
        if (page_size != 0 && layout->page_size != page_size) {
            fail(check, where + ": page size differs from other nodes");
        }
        page_size = layout->page_size;
        const double size = page_size;
        const scene::Mesh& mesh = prepared.meshes.at(static_cast<std::size_t>(node.mesh));
        for (const scene::LightmapSurface& surface : layout->surfaces) {
            const double texel_size = surface.texel_size > 0.0
                                          ? surface.texel_size
                                          : static_cast<double>(layout->texel_size);
            const double texel_area = texel_size * texel_size;
            ++check.surfaces;
            const std::string at = where + " surface " + std::to_string(surface.id);
            if (surface.primitive < 0 ||
                static_cast<std::size_t>(surface.primitive) >= mesh.primitives.size()) {
                fail(check, at + ": no such primitive");
                continue;
            }
            const scene::Primitive& p =
                mesh.primitives[static_cast<std::size_t>(surface.primitive)];
            if (p.texcoords1.size() != p.positions.size()) {
                fail(check, at + ": no TEXCOORD_1");
                continue;
            }
            // Triangles of each chart, in texels relative to the chart's rectangle.
            std::vector<std::vector<glm::dvec2>> chart_uv(surface.charts.size());
            std::vector<std::vector<std::array<int, 3>>> chart_triangles(surface.charts.size());
            for (std::size_t t = 0; t + 2 < p.indices.size(); t += 3) {
                ++check.triangles;
                std::array<glm::dvec2, 3> uv{};
                std::array<glm::dvec3, 3> position{};
                for (std::size_t k = 0; k < 3; ++k) {
                    uv[k] = glm::dvec2(p.texcoords1[p.indices[t + k]]) * size;
                    position[k] =
                        glm::dvec3(world[n] * glm::vec4(p.positions[p.indices[t + k]], 1.0f));
                }
                const glm::dvec2 low = glm::min(uv[0], glm::min(uv[1], uv[2]));
                const glm::dvec2 high = glm::max(uv[0], glm::max(uv[1], uv[2]));
                int owner = -1;
                for (std::size_t c = 0; c < surface.charts.size(); ++c) {
                    const scene::TexelRect& r = surface.charts[c];
                    if (low.x >= r.x && low.y >= r.y && high.x <= r.x + r.width &&
                        high.y <= r.y + r.height) {
                        owner = owner < 0 ? static_cast<int>(c) : -2;
                    }
                }
                if (owner < 0) {
                    fail(check, at + ": triangle " + std::to_string(t / 3) +
                                    (owner == -1 ? " lies in no chart" : " lies in two charts"));
                    continue;
                }
                const scene::TexelRect& r = surface.charts[static_cast<std::size_t>(owner)];
                const auto base =
                    static_cast<int>(chart_uv[static_cast<std::size_t>(owner)].size());
                for (const auto& v : uv) {
                    chart_uv[static_cast<std::size_t>(owner)].push_back(v - glm::dvec2(r.x, r.y));
                }
                chart_triangles[static_cast<std::size_t>(owner)].push_back(
                    {base, base + 1, base + 2});
                // Area stretch: world area per texel against texel_size^2.
                const double uv_area = 0.5 * ((uv[1].x - uv[0].x) * (uv[2].y - uv[0].y) -
                                              (uv[1].y - uv[0].y) * (uv[2].x - uv[0].x));
                const double world_area = 0.5 * glm::length(glm::cross(position[1] - position[0],
                                                                       position[2] - position[0]));
                if (!(uv_area > 0.0)) {
                    fail(check, at + ": triangle " + std::to_string(t / 3) +
                                    " is flipped or collapsed in UV");
                    continue;
                }
                const double stretch = world_area / texel_area / uv_area;
                check.stretch_min = std::min(check.stretch_min, stretch);
                check.stretch_max = std::max(check.stretch_max, stretch);
                // A little room for UVs rounded to float in the file.
                if (stretch > max_stretch * 1.005 || stretch < 1.0 / (max_stretch * 1.005)) {
                    std::ostringstream message;
                    message << at << ": triangle " << t / 3 << " has area stretch " << stretch;
                    fail(check, message.str());
                }
            }
            std::int64_t texels = 0;
            for (std::size_t c = 0; c < surface.charts.size(); ++c) {
                ++check.charts;
                const scene::TexelRect& r = surface.charts[c];
                std::int64_t outside = 0;
                const prep::CoverageMask mask =
                    prep::cover(chart_uv[c], chart_triangles[c], r.width, r.height, &outside);
                texels += mask.count();
                if (outside != 0) {
                    fail(check, at + ": chart " + std::to_string(c) +
                                    " covers texels outside its rectangle");
                }
                // Independently: every texel a triangle overlaps is one of the chart's.
                for (const auto& tri : chart_triangles[c]) {
                    const std::array<glm::dvec2, 3> corners{
                        chart_uv[c][static_cast<std::size_t>(tri[0])],
                        chart_uv[c][static_cast<std::size_t>(tri[1])],
                        chart_uv[c][static_cast<std::size_t>(tri[2])]};
                    const glm::dvec2 low = glm::min(corners[0], glm::min(corners[1], corners[2]));
                    const glm::dvec2 high = glm::max(corners[0], glm::max(corners[1], corners[2]));
                    for (int y = static_cast<int>(std::floor(low.y)); y < high.y; ++y) {
                        for (int x = static_cast<int>(std::floor(low.x)); x < high.x; ++x) {
                            if (overlap_area(corners, x, y) <= 1e-6) {
                                continue;
                            }
                            if (x < 0 || y < 0 || x >= r.width || y >= r.height || !mask.at(x, y)) {
                                fail(check, at + ": chart " + std::to_string(c) +
                                                " does not cover texel (" +
                                                std::to_string(r.x + x) + ", " +
                                                std::to_string(r.y + y) + ") under a triangle");
                            }
                        }
                    }
                }
                if (folds_over(chart_uv[c], chart_triangles[c], r.width, r.height)) {
                    fail(check, at + ": chart " + std::to_string(c) + " folds over itself");
                }
                // Claim the chart's texels and its padding on the page.
                const prep::CoverageMask grown = prep::dilate(mask, padding);
                auto& page = claims[surface.page];
                if (page.empty()) {
                    page.assign(
                        static_cast<std::size_t>(page_size) * static_cast<std::size_t>(page_size),
                        -1);
                }
                const int id = chart_counter++;
                for (int y = 0; y < grown.height; ++y) {
                    for (int x = 0; x < grown.width; ++x) {
                        if (!grown.at(x, y)) {
                            continue;
                        }
                        const int px = r.x - padding + x;
                        const int py = r.y - padding + y;
                        if (px < 0 || py < 0 || px >= page_size || py >= page_size) {
                            fail(check, at + ": chart " + std::to_string(c) +
                                            " with padding leaves the page");
                            continue;
                        }
                        int& owner = page[static_cast<std::size_t>(py) *
                                              static_cast<std::size_t>(page_size) +
                                          static_cast<std::size_t>(px)];
                        if (owner >= 0 && owner != id) {
                            fail(check, at + ": texel (" + std::to_string(px) + ", " +
                                            std::to_string(py) + ") on page " +
                                            std::to_string(surface.page) + " is claimed twice");
                        }
                        owner = id;
                    }
                }
            }
            if (texels != surface.texels) {
                fail(check, at + ": covers " + std::to_string(texels) + " texels, the table says " +
                                std::to_string(surface.texels));
            }
            check.texels += texels;
        }
    }
    check.page_texels = static_cast<std::int64_t>(claims.size()) * page_size * page_size;
    return check;
}

}  // namespace luxel::testing
