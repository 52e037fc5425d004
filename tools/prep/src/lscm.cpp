// Least-squares conformal maps (Lévy, Petitjean, Ray, Maillot, SIGGRAPH 2002), set up from the
// gradient form of the Cauchy-Riemann equations and solved through the normal equations.

#include <algorithm>
#include <cmath>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include "parameterization.hpp"

namespace luxel::prep::detail {
namespace {

/// The two vertices pinned to fix the map's position, rotation and scale: the extremes of the
/// piece along its longest bounding-box axis, which keeps the solution well conditioned.
std::array<int, 2> pick_pins(const Patch& patch, const Piece& piece) {
    glm::dvec3 low(std::numeric_limits<double>::max());
    glm::dvec3 high(std::numeric_limits<double>::lowest());
    for (const int v : piece.vertices) {
        low = glm::min(low, patch.positions[static_cast<std::size_t>(v)]);
        high = glm::max(high, patch.positions[static_cast<std::size_t>(v)]);
    }
    const glm::dvec3 extent = high - low;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0
                     : extent.y >= extent.z                       ? 1
                                                                  : 2;
    std::array<int, 2> pins{0, 0};
    for (std::size_t i = 0; i < piece.vertices.size(); ++i) {
        const double c = patch.positions[static_cast<std::size_t>(piece.vertices[i])][axis];
        const double lowest = patch.positions[static_cast<std::size_t>(
            piece.vertices[static_cast<std::size_t>(pins[0])])][axis];
        const double highest = patch.positions[static_cast<std::size_t>(
            piece.vertices[static_cast<std::size_t>(pins[1])])][axis];
        if (c < lowest) {
            pins[0] = static_cast<int>(i);
        }
        if (c > highest) {
            pins[1] = static_cast<int>(i);
        }
    }
    return pins;
}

}  // namespace

std::optional<std::vector<glm::dvec2>> conformal_map(const Patch& patch, const Piece& piece) {
    const std::size_t vertex_count = piece.vertices.size();
    const std::array<int, 2> pins = pick_pins(patch, piece);
    if (pins[0] == pins[1] || vertex_count < 3) {
        return std::nullopt;
    }
    const double pin_distance =
        glm::length(patch.positions[static_cast<std::size_t>(
                        piece.vertices[static_cast<std::size_t>(pins[1])])] -
                    patch.positions[static_cast<std::size_t>(
                        piece.vertices[static_cast<std::size_t>(pins[0])])]);
    // Unknowns: (u, v) of every free vertex, interleaved. Pinned vertices sit at (0, 0) and
    // (pin_distance, 0).
    std::vector<int> unknown(vertex_count, -1);
    std::vector<glm::dvec2> pinned(vertex_count, glm::dvec2(0.0));
    pinned[static_cast<std::size_t>(pins[1])] = glm::dvec2(pin_distance, 0.0);
    int free_count = 0;
    for (std::size_t v = 0; v < vertex_count; ++v) {
        if (static_cast<int>(v) != pins[0] && static_cast<int>(v) != pins[1]) {
            unknown[v] = free_count++;
        }
    }

    // Per triangle, in a frame of its own plane: with the gradients g_j of the linear basis
    // functions, the map is conformal where grad v is grad u turned a quarter counter-clockwise:
    //   sum_j (g_j.y u_j + g_j.x v_j) = 0   and   sum_j (g_j.y v_j - g_j.x u_j) = 0,
    // each weighted by sqrt(area) so the residual integrates over the surface.
    const std::size_t face_count = piece.faces.size();
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(face_count * 12);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(2 * face_count));
    for (std::size_t f = 0; f < face_count; ++f) {
        const auto& c = piece.corners[f];
        const auto face = static_cast<std::size_t>(piece.faces[f]);
        std::array<glm::dvec3, 3> p{};
        for (std::size_t j = 0; j < 3; ++j) {
            p[j] = patch.positions[static_cast<std::size_t>(
                piece.vertices[static_cast<std::size_t>(c[j])])];
        }
        const glm::dvec3 x_axis = glm::normalize(p[1] - p[0]);
        const glm::dvec3 y_axis = glm::cross(patch.normals[face], x_axis);
        const std::array<glm::dvec2, 3> q{
            glm::dvec2(0.0), glm::dvec2(glm::length(p[1] - p[0]), 0.0),
            glm::dvec2(glm::dot(p[2] - p[0], x_axis), glm::dot(p[2] - p[0], y_axis))};
        const double twice_area = q[1].x * q[2].y;
        if (!(twice_area > 0.0)) {
            return std::nullopt;
        }
        const double weight = std::sqrt(0.5 * twice_area);
        const auto row_x = static_cast<int>(2 * f);
        const int row_y = row_x + 1;
        for (std::size_t j = 0; j < 3; ++j) {
            // Gradient of vertex j's hat function: the opposite edge turned a quarter
            // counter-clockwise, over twice the area.
            const glm::dvec2 edge = q[(j + 2) % 3] - q[(j + 1) % 3];
            const glm::dvec2 g = glm::dvec2(-edge.y, edge.x) / twice_area * weight;
            const auto vertex = static_cast<std::size_t>(c[j]);
            // Coefficients of u_j and v_j in the two rows.
            const double u_in_x = g.y;
            const double v_in_x = g.x;
            const double u_in_y = -g.x;
            const double v_in_y = g.y;
            if (unknown[vertex] >= 0) {
                const int column = 2 * unknown[vertex];
                entries.emplace_back(row_x, column, u_in_x);
                entries.emplace_back(row_x, column + 1, v_in_x);
                entries.emplace_back(row_y, column, u_in_y);
                entries.emplace_back(row_y, column + 1, v_in_y);
            } else {
                const glm::dvec2 known = pinned[vertex];
                rhs[row_x] -= u_in_x * known.x + v_in_x * known.y;
                rhs[row_y] -= u_in_y * known.x + v_in_y * known.y;
            }
        }
    }
    Eigen::SparseMatrix<double> system(static_cast<Eigen::Index>(2 * face_count), 2 * free_count);
    system.setFromTriplets(entries.begin(), entries.end());
    const Eigen::SparseMatrix<double> transposed = system.transpose();
    const Eigen::SparseMatrix<double> normal = transposed * system;
    const Eigen::VectorXd normal_rhs = transposed * rhs;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(normal);
    if (solver.info() != Eigen::Success) {
        return std::nullopt;
    }
    const Eigen::VectorXd solution = solver.solve(normal_rhs);
    if (solver.info() != Eigen::Success || !solution.allFinite()) {
        return std::nullopt;
    }
    std::vector<glm::dvec2> uv(vertex_count);
    for (std::size_t v = 0; v < vertex_count; ++v) {
        uv[v] = unknown[v] < 0 ? pinned[v]
                               : glm::dvec2(solution[2 * unknown[v]], solution[2 * unknown[v] + 1]);
    }
    return uv;
}

}  // namespace luxel::prep::detail
