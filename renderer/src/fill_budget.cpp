#include "fill_budget.hpp"

#include <algorithm>
#include <array>

namespace luxel::renderer {

double projected_texels(const Bounds& world, const glm::mat4& view_projection, int width,
                        int height) {
    const double full = static_cast<double>(width) * static_cast<double>(height);
    if (world.empty()) {
        return 0.0;
    }
    std::array<glm::vec4, 8> clip{};
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p((corner & 1) != 0 ? world.hi.x : world.lo.x,
                          (corner & 2) != 0 ? world.hi.y : world.lo.y,
                          (corner & 4) != 0 ? world.hi.z : world.lo.z);
        clip[static_cast<std::size_t>(corner)] = view_projection * glm::vec4(p, 1.0f);
    }
    // Outside the view when every corner is beyond one side of it, behind the eye included:
    // the clip-space test of a box against a frustum.
    const auto all_outside = [&](auto outside) {
        return std::all_of(clip.begin(), clip.end(), outside);
    };
    if (all_outside([](const glm::vec4& c) { return c.x < -c.w; }) ||
        all_outside([](const glm::vec4& c) { return c.x > c.w; }) ||
        all_outside([](const glm::vec4& c) { return c.y < -c.w; }) ||
        all_outside([](const glm::vec4& c) { return c.y > c.w; }) ||
        all_outside([](const glm::vec4& c) { return !(c.w > 1e-6f); })) {
        return 0.0;
    }
    glm::vec2 lo(1e30f);
    glm::vec2 hi(-1e30f);
    for (const glm::vec4& c : clip) {
        // A corner at or behind the eye projects to infinity or flips: the box may then cover
        // any part of the view, so it is counted as all of it.
        if (!(c.w > 1e-6f)) {
            return full;
        }
        const glm::vec2 ndc = glm::vec2(c) / c.w;
        lo = glm::min(lo, ndc);
        hi = glm::max(hi, ndc);
    }
    lo = glm::clamp(lo, glm::vec2(-1.0f), glm::vec2(1.0f));
    hi = glm::clamp(hi, glm::vec2(-1.0f), glm::vec2(1.0f));
    const double cover_x = std::max(0.0, static_cast<double>(hi.x - lo.x)) * 0.5;
    const double cover_y = std::max(0.0, static_cast<double>(hi.y - lo.y)) * 0.5;
    return cover_x * cover_y * full;
}

double primitive_texels(const GpuPrimitive& primitive, double rect_texels) {
    const double triangles = static_cast<double>(primitive.index_count / 3);
    return rect_texels * std::min(static_cast<double>(primitive.layers), triangles);
}

}  // namespace luxel::renderer
