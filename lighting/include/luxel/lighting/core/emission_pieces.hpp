#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/scene/scene.hpp"

namespace luxel::lighting {

/// What an area light emits at its emissive texture's resolution: each triangle cut into
/// level^2 pieces by a regular subdivision of its barycentric coordinates, each piece with the
/// texture's mean radiance over it. Photons then leave from where the texture is bright (a
/// small emissive patch emits from the patch, not from the whole triangle under it), and the
/// reference sees the same radiance where its rays hit. The pieces do not depend on where the
/// light is, so a moving emitter keeps its pieces.
///
/// Barycentric coordinates (s, q): the point a + s (b - a) + q (c - a) of triangle (a, b, c).
/// With level n the unit triangle s, q >= 0, s + q <= 1 is cut into cells (i, j), i + j < n,
/// each into a lower piece (s + q below the cell's diagonal) and, where i + j < n - 1, an upper
/// one. Pieces are numbered row by row (j), and within a row lower/upper alternately by i.
class EmissionPieces {
  public:
    /// At most this many pieces per light (about 5 MiB with its sampler): a texture finer than
    /// that over a large emitter is averaged over larger pieces.
    static constexpr std::size_t kMaxPieces = std::size_t{1} << 18;
    /// At most this level per triangle (4096 pieces).
    static constexpr std::uint32_t kMaxLevel = 64;

    /// Appends a triangle with `radiance.size()` = level^2 pieces in piece order.
    void add(std::uint32_t level, const std::vector<glm::vec3>& radiance);

    /// The pieces of every emissive primitive of `mesh` in order (the triangles an area light
    /// emits from, as LightGroups lists them), from `scene`'s materials and emissive textures:
    /// a triangle of an untextured material is one piece of its emitted radiance; a textured
    /// one is cut so a piece covers about one texel, within kMaxLevel and kMaxPieces. Throws
    /// luxel::Error naming the file when an emissive texture does not decode.
    [[nodiscard]] static EmissionPieces of_mesh(const scene::Scene& scene, const scene::Mesh& mesh);

    /// Every piece has the same radiance (an untextured emitter of one material).
    [[nodiscard]] bool uniform() const;
    [[nodiscard]] std::size_t triangle_count() const { return level_.size(); }
    [[nodiscard]] std::size_t piece_count() const { return radiance_.size(); }
    [[nodiscard]] std::uint32_t level(std::size_t triangle) const { return level_[triangle]; }
    [[nodiscard]] std::size_t first_piece(std::size_t triangle) const { return first_[triangle]; }
    /// Radiance W/(m^2 sr) of a piece of a triangle (before the AreaLight's scale).
    [[nodiscard]] const glm::vec3& radiance(std::size_t triangle, std::uint32_t piece) const {
        return radiance_[first_[triangle] + piece];
    }

    /// The piece of a level-`level` triangle that holds barycentric (s, q) (clamped into the
    /// triangle).
    [[nodiscard]] static std::uint32_t piece_at(std::uint32_t level, glm::dvec2 sq);
    /// The barycentric corners of a piece.
    [[nodiscard]] static std::array<glm::dvec2, 3> corners(std::uint32_t level,
                                                           std::uint32_t piece);

  private:
    std::vector<std::uint32_t> level_;
    std::vector<std::size_t> first_;
    std::vector<glm::vec3> radiance_;
};

}  // namespace luxel::lighting
