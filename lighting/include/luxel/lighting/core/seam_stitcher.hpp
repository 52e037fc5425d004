#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <unordered_map>
#include <vector>

#include "luxel/lighting/core/iim_page.hpp"
#include "luxel/lighting/core/light_map_seams.hpp"

namespace luxel::lighting {

/// Makes the IIM's two sides of every seam agree after each pass commits (docs/METHOD.md
/// §6.13). Per object, the texels the seams' bilinear lookups read are moved as little as
/// possible while the lookups on both sides come to agree: the least-squares problem
///     min  sum_t (x_t - g_t)^2 + w sum_s (lookup_a(s) - lookup_b(s))^2
/// over the texels t those lookups touch (g: what the passes gathered), whose normal equations
/// (I + w J^T J) x = g have one sparse matrix per object, factored once (Eigen's
/// SimplicialLDLT) and solved per channel at each commit. Every other texel is left as
/// gathered. The gathered values are kept apart from what the stitcher wrote, so stitching
/// again starts from the gathers, never from its own output, and nothing drifts.
class SeamStitcher {
  public:
    /// How strongly a sample's two lookups are pulled together against a texel keeping its
    /// gathered value: with two samples per texel, the two sides of a seam end within about 4%
    /// of their gathered difference (SeamStitcher.BothSidesAgreeAndOnlyTheSeamsTexelsMove), and
    /// the step is spread over the two texels on each side the lookups read.
    static constexpr double kSeamWeight = 16.0;

    SeamStitcher();
    ~SeamStitcher();
    SeamStitcher(const SeamStitcher&) = delete;
    SeamStitcher& operator=(const SeamStitcher&) = delete;

    /// Takes in one object's seams (find_seams): one system over the texels its samples read,
    /// on the pages `pages` describes (their sizes). Nothing is kept for an object without
    /// samples.
    void add_object(std::vector<SeamSample> samples, std::span<const IimPage> pages);

    /// After a pass committed `surface`'s texels: stitches the seams of its object, once every
    /// surface on them has committed a pass (before that, one side would be pulled towards
    /// texels nothing has gathered yet). Texels it changes fade from what they show to the
    /// stitched value over `fade_seconds` (IimPage::commit) and are marked changed.
    void stitch(std::uint32_t surface, std::span<IimPage> pages, double now_seconds,
                double fade_seconds);

    /// Every object's samples, for measuring (seam_mismatch).
    [[nodiscard]] std::vector<SeamSample> samples() const;
    /// Texels the objects' systems move (what they cost: a float triple and a matrix row each).
    [[nodiscard]] std::size_t texels() const;
    /// Stitches done so far.
    [[nodiscard]] std::uint64_t stitches() const { return stitches_; }

  private:
    struct Object;
    std::vector<std::unique_ptr<Object>> objects_;
    std::unordered_map<std::uint32_t, std::size_t> object_of_;  ///< surface -> object
    std::unordered_map<std::uint32_t, bool> committed_;         ///< surfaces with a pass in
    std::uint64_t stitches_ = 0;
};

}  // namespace luxel::lighting
