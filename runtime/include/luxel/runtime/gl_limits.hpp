#pragma once

namespace luxel::gl {

/// The largest width and height, in texels, a texture bound as a framebuffer's attachment can
/// have on the current context: the least of the driver's texture, framebuffer and
/// renderbuffer limits (16,384 on llvmpipe).
[[nodiscard]] int largest_render_target();

}  // namespace luxel::gl
