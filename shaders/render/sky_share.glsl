// How much of a pixel shows the sky, from SkyCoverage's mask (docs/METHOD.md §8.6): read by
// the composite and by the mask of the pixels its second pass finishes (sky_fill_mask.frag).

// The sky mask (renderer/src/sky_coverage.hpp): u_coverage_scale^2 sub-samples per pixel, 1
// where a surface covers one; u_coverage_scale 0 when there is none.
layout(binding = 10) uniform sampler2D u_coverage;
uniform int u_coverage_scale;

// The share of the pixel's sub-samples that show the sky (0 without a mask).
float sky_share(ivec2 pixel) {
    if (u_coverage_scale <= 0) {
        return 0.0;
    }
    float covered = 0.0;
    ivec2 base = pixel * u_coverage_scale;
    for (int y = 0; y < u_coverage_scale; ++y) {
        for (int x = 0; x < u_coverage_scale; ++x) {
            covered += texelFetch(u_coverage, base + ivec2(x, y), 0).r;
        }
    }
    return 1.0 - covered / float(u_coverage_scale * u_coverage_scale);
}
