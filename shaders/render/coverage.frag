#version 450 core
// Sky-edge coverage (renderer/src/sky_coverage.hpp): every sub-sample a surface covers is 1;
// the target was cleared to 0, the sky.

layout(location = 0) out float o_covered;

void main() {
    o_covered = 1.0;
}
