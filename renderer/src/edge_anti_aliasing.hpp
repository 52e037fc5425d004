#pragma once

#include "frame_targets.hpp"
#include "luxel/runtime/program.hpp"

namespace luxel {
class ShaderLibrary;
}

namespace luxel::renderer {

/// Anti-aliasing of the composed frame where the G-buffer shows two surfaces meeting
/// (shaders/post/edge_aa.frag, docs/METHOD.md §8.4): reads FrameTargets::composed and the
/// G-buffer's positions and normals, writes FrameTargets::frame. Pixels away from geometric
/// edges are copied exactly, so flat regions, textures, shadows and light maps are untouched:
/// the frame is copied whole, a mask pass marks the edge pixels in FrameTargets::stencil
/// (shaders/post/edge_mask.frag) and the filter runs under the stencil test, so only blocks
/// with an edge pixel are shaded by it.
class EdgeAntiAliasing {
  public:
    explicit EdgeAntiAliasing(const ShaderLibrary& shaders);

    /// Draws into targets.frame_target with a full-screen triangle; the caller binds the empty
    /// vertex array and restores state (FrameRenderer's StateGuard).
    /// `sky_resolved`: the composite already mixed surfaces and sky by their coverage
    /// (SkyCoverage), so a pixel next to the sky is not an edge to filter.
    void run(const FrameTargets& targets, bool sky_resolved) const;

  private:
    gl::Program mask_;
    gl::Program program_;
};

}  // namespace luxel::renderer
