// The sky's radiance along a direction, from the equirectangular texture SkyTexture uploads:
// the layout of lighting::SkyRadiance (+y up; row 0 the zenith; azimuth atan2(z, x) from 0 at
// +x to 2 pi). Texture row t is texel coordinate t, so v = theta / pi needs no flip.

const float kSkyPi = 3.14159265358979;

vec3 sky_radiance(sampler2D sky, vec3 direction) {
    vec3 d = normalize(direction);
    float theta = acos(clamp(d.y, -1.0, 1.0));
    float phi = atan(d.z, d.x);
    if (phi < 0.0) {
        phi += 2.0 * kSkyPi;
    }
    // textureLod: the derivative of the azimuth jumps where it wraps, which would pick the
    // coarsest level along that seam; the texture has one level anyway.
    return textureLod(sky, vec2(phi / (2.0 * kSkyPi), theta / kSkyPi), 0.0).rgb;
}
