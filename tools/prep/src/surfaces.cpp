#include "luxel/prep/surfaces.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <numeric>
#include <unordered_map>

#include <glm/gtc/constants.hpp>

namespace luxel::prep {
namespace {

/// Union-find over face indices. The root of a set is always its smallest member, which makes
/// the components independent of the order edges are visited in.
class DisjointSets {
  public:
    explicit DisjointSets(std::size_t n) : parent_(n) {
        std::iota(parent_.begin(), parent_.end(), 0);
    }
    int find(int x) {
        while (parent_[static_cast<std::size_t>(x)] != x) {
            // Path halving: every other node on the way up skips to its grandparent.
            const int grandparent =
                parent_[static_cast<std::size_t>(parent_[static_cast<std::size_t>(x)])];
            parent_[static_cast<std::size_t>(x)] = grandparent;
            x = grandparent;
        }
        return x;
    }
    void unite(int a, int b) {
        a = find(a);
        b = find(b);
        if (a != b) {
            parent_[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
        }
    }

  private:
    std::vector<int> parent_;
};

bool connected(const Face& a, const Face& b, double cos_crease) {
    // "Below the crease angle": the angle between the normals is strictly smaller.
    return a.material == b.material && glm::dot(a.normal, b.normal) > cos_crease;
}

}  // namespace

std::vector<CreaseSurface> find_crease_surfaces(const NodeGeometry& geometry,
                                                double crease_degrees) {
    const std::size_t face_count = geometry.faces.size();
    const double cos_crease = std::cos(glm::radians(crease_degrees));
    DisjointSets sets(face_count);
    for (std::size_t f = 0; f < face_count; ++f) {
        const Face& face = geometry.faces[f];
        for (const int neighbour : face.neighbours) {
            // Each edge is seen from both sides; uniting once is enough.
            if (neighbour > static_cast<int>(f) &&
                connected(face, geometry.faces[static_cast<std::size_t>(neighbour)], cos_crease)) {
                sets.unite(static_cast<int>(f), neighbour);
            }
        }
    }
    std::vector<CreaseSurface> surfaces;
    std::vector<int> surface_of_root(face_count, -1);
    for (std::size_t f = 0; f < face_count; ++f) {
        const auto root = static_cast<std::size_t>(sets.find(static_cast<int>(f)));
        if (surface_of_root[root] < 0) {
            surface_of_root[root] = static_cast<int>(surfaces.size());
            surfaces.emplace_back();
            surfaces.back().material = geometry.faces[f].material;
        }
        CreaseSurface& surface = surfaces[static_cast<std::size_t>(surface_of_root[root])];
        surface.faces.push_back(static_cast<int>(f));
        surface.area += geometry.faces[f].area;
    }
    return surfaces;
}

double max_connected_dihedral_degrees(const NodeGeometry& geometry) {
    double smallest_cos = 1.0;
    for (const Face& face : geometry.faces) {
        for (const int neighbour : face.neighbours) {
            if (neighbour >= 0) {
                const Face& other = geometry.faces[static_cast<std::size_t>(neighbour)];
                if (other.material == face.material) {
                    smallest_cos = std::min(smallest_cos, glm::dot(face.normal, other.normal));
                }
            }
        }
    }
    return glm::degrees(std::acos(std::clamp(smallest_cos, -1.0, 1.0)));
}

std::vector<std::vector<int>> group_charts(const NodeGeometry& geometry,
                                           const std::vector<std::vector<int>>& chart_faces,
                                           const std::vector<double>& chart_area,
                                           double area_budget) {
    const std::size_t chart_count = chart_faces.size();
    std::unordered_map<int, int> chart_of_face;
    for (std::size_t c = 0; c < chart_count; ++c) {
        for (const int f : chart_faces[c]) {
            chart_of_face.emplace(f, static_cast<int>(c));
        }
    }
    // Chart adjacency across shared edges, sorted so the walk below is deterministic.
    std::vector<std::vector<int>> adjacent(chart_count);
    for (std::size_t c = 0; c < chart_count; ++c) {
        for (const int f : chart_faces[c]) {
            for (const int neighbour : geometry.faces[static_cast<std::size_t>(f)].neighbours) {
                const auto found = chart_of_face.find(neighbour);
                if (found != chart_of_face.end() && found->second != static_cast<int>(c)) {
                    adjacent[c].push_back(found->second);
                }
            }
        }
        std::sort(adjacent[c].begin(), adjacent[c].end());
        adjacent[c].erase(std::unique(adjacent[c].begin(), adjacent[c].end()), adjacent[c].end());
    }

    std::vector<std::vector<int>> groups;
    std::vector<bool> assigned(chart_count, false);
    for (std::size_t seed = 0; seed < chart_count; ++seed) {
        if (assigned[seed]) {
            continue;
        }
        std::vector<int> group{static_cast<int>(seed)};
        assigned[seed] = true;
        double area = chart_area[seed];
        std::deque<int> frontier{static_cast<int>(seed)};
        while (!frontier.empty()) {
            const int current = frontier.front();
            frontier.pop_front();
            for (const int next : adjacent[static_cast<std::size_t>(current)]) {
                const auto n = static_cast<std::size_t>(next);
                if (assigned[n] || area + chart_area[n] > area_budget) {
                    continue;
                }
                assigned[n] = true;
                area += chart_area[n];
                group.push_back(next);
                frontier.push_back(next);
            }
        }
        std::sort(group.begin(), group.end());
        groups.push_back(std::move(group));
    }
    return groups;
}

}  // namespace luxel::prep
