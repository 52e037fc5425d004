#pragma once

#include "luxel/runtime/gl_objects.hpp"

namespace luxel::renderer {

/// The frame-sized textures of the renderer: the G-buffer and one target per composition
/// term. Terms are RGBA32F so the linear frame keeps full float precision end to end (the
/// error measurements read it back); G-buffer attributes that need less are RGBA16F.
struct FrameTargets {
    int width = 0;
    int height = 0;

    // G-buffer (shaders/render/gbuffer.frag), one framebuffer with six colour attachments.
    gl::Texture albedo;    ///< RGBA16F: diffuse albedo, a = 1 where specular
    gl::Texture normal;    ///< RGBA16F: world normal
    gl::Texture position;  ///< RGBA32F: world position, w = 1 where covered
    gl::Texture lightmap;  ///< RGBA32F: light-map uv, page layer, content
    gl::Texture emission;  ///< RGBA16F: emitted radiance
    gl::Texture specular;  ///< RGBA16F: F0, transmission
    /// DEPTH32F_STENCIL8. The stencil is 1 where the visible surface has no light map (the
    /// G-buffer pass writes it), so the probes' indirect light runs on those pixels only.
    gl::Texture depth;
    gl::Framebuffer gbuffer;

    // One framebuffer per term, each with its texture as colour attachment 0.
    gl::Texture direct;
    gl::Framebuffer direct_target;
    gl::Texture indirect;
    gl::Framebuffer indirect_target;
    gl::Texture specular_term;
    gl::Framebuffer specular_target;
    gl::Texture frame;
    gl::Framebuffer frame_target;
    /// With anti-aliasing only: the composite's sum, before the edges are smoothed into
    /// `frame`. Bilinear, since the edge pass reads between pixels. Without anti-aliasing the
    /// composite writes `frame` and these stay empty.
    gl::Texture composed;
    gl::Framebuffer composed_target;
    /// STENCIL_INDEX8 on `frame_target` and `composed_target`, made by ensure_stencil() for the
    /// passes that run on marked pixels only: the edge pass (EdgeAntiAliasing) and the
    /// composite's mixing by the sky mask. Empty until one of them needs it.
    gl::Renderbuffer stencil;

    /// Allocates everything at `width` x `height` (throws luxel::Error for a bad size or an
    /// incomplete framebuffer); `anti_aliasing` adds the composed target.
    FrameTargets(int width, int height, bool anti_aliasing);
    FrameTargets() = default;

    /// Makes `stencil` and attaches it, once.
    void ensure_stencil();
};

}  // namespace luxel::renderer
