#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "luxel/lighting/core/caustic_photons.hpp"
#include "luxel/lighting/core/photon_world.hpp"
#include "luxel/runtime/gl_objects.hpp"

namespace luxel::lighting {

/// The caustic photons on the GPU: one shader storage buffer of CausticPhoton (the 32-byte
/// layout is read as it is by shaders/caustics/splat.vert) and the (first, count) ranges to
/// draw. For PhotonWorld's lists every (pair, slice) owns a fixed range of its slice's full
/// size, so a retraced slice is rewritten in place and the others are not touched.
class CausticPhotonBuffer {
  public:
    void upload(std::span<const CausticPhoton> photons);
    void upload(std::span<const CausticPair> pairs);

    [[nodiscard]] GLuint buffer() const { return buffer_.id(); }
    [[nodiscard]] std::span<const GLint> firsts() const { return firsts_; }
    [[nodiscard]] std::span<const GLsizei> counts() const { return counts_; }
    [[nodiscard]] std::uint32_t photon_count() const { return photon_count_; }
    [[nodiscard]] std::uint64_t slices_uploaded() const { return slices_uploaded_; }
    [[nodiscard]] std::uint64_t bytes_uploaded() const { return bytes_uploaded_; }

  private:
    /// What was uploaded of one (pair, slice): a slice is rewritten when either changes. The
    /// size is compared too because a pair replaced by a new list of the same entities starts
    /// its retrace count again and could meet the old count.
    struct SliceRecord {
        std::uint64_t retraces = 0;
        std::size_t stored = 0;
        std::size_t offset = 0;  ///< first photon of the slice's fixed range
    };
    struct PairRecord {
        ecs::Entity generator;
        ecs::Entity light;
        std::uint32_t photon_count = 0;
        std::vector<SliceRecord> slices;
    };

    [[nodiscard]] bool same_layout(std::span<const CausticPair> pairs) const;
    /// Makes room for `photons`; returns true when the buffer was (re)created, which loses
    /// its contents.
    bool reserve(std::size_t photons);
    void write(std::size_t offset, std::span<const CausticPhoton> photons);
    void rebuild_ranges();

    gl::Buffer buffer_;
    std::vector<PairRecord> pairs_;
    std::vector<GLint> firsts_;
    std::vector<GLsizei> counts_;
    std::uint32_t photon_count_ = 0;
    std::uint64_t slices_uploaded_ = 0;
    std::uint64_t bytes_uploaded_ = 0;
};

}  // namespace luxel::lighting
