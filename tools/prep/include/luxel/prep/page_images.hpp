#pragma once

#include <filesystem>
#include <vector>

#include "luxel/prep/prep.hpp"
#include "luxel/runtime/image.hpp"

namespace luxel::prep {

/// One page as a picture: each surface in its own colour, its charts' padding in a darker
/// shade of it, unused texels dark grey. Small pages are enlarged (nearest neighbour) so a
/// texel stays visible.
[[nodiscard]] Image render_page(const PrepResult& result, int page);

/// The colour of a surface in the page pictures (linear RGB, distinct for nearby ids).
[[nodiscard]] glm::vec3 surface_colour(int surface_id);

/// Writes `<stem>.page<k>.png` for every page; returns the files written. Throws luxel::Error
/// naming the file when it cannot write.
std::vector<std::filesystem::path> write_page_images(const PrepResult& result,
                                                     const std::filesystem::path& stem);

}  // namespace luxel::prep
