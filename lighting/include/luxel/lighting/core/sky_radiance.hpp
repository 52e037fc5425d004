#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

/// The sky: radiance arriving from every direction at infinity, W/(m^2 sr), linear RGB, and the
/// distribution that samples it (docs/METHOD.md §6.11).
namespace luxel::lighting {

/// Radiance over the sphere of directions as an equirectangular grid of constant cells. Every
/// kind of sky is one: a uniform sky is two rows (the upper hemisphere and a black ground), an
/// environment map is its pixels. +y is up (glTF); row 0 is the zenith, the last row the nadir,
/// and column c covers azimuths phi = atan2(z, x) in [2 pi c / W, 2 pi (c + 1) / W).
///
/// Each cell is constant over its solid angle and is sampled uniformly in solid angle, so
/// `radiance`, `sample` and `pdf` agree exactly: an estimate that weighs a sample by
/// radiance / pdf is unbiased for any grid, the two-row uniform sky included.
class SkyRadiance {
  public:
    /// Black everywhere.
    SkyRadiance();
    /// `cells` holds width x height radiances, row by row from the zenith. Negative, NaN and
    /// infinite values read as 0, values over kMaxRadiance as kMaxRadiance. Throws luxel::Error
    /// when the sizes do not match or exceed kMaxCells.
    SkyRadiance(int width, int height, std::vector<glm::vec3> cells);

    /// `radiance` from every direction above the horizon (y > 0), none from below it: the
    /// level's own ground, if it has one, bounces the light.
    [[nodiscard]] static SkyRadiance uniform(const glm::vec3& radiance);

    /// The largest radiance a cell keeps, W/(m^2 sr): 50 times the sun's disc, and far enough
    /// from float's range that scaled and summed values stay finite.
    static constexpr float kMaxRadiance = 1e9f;
    /// Grids larger than this are refused (4096 x 2048: about 100 MB with the sampling tables).
    static constexpr std::size_t kMaxCells = std::size_t{4096} * 2048;

    /// The radiance arriving from direction `towards_sky` (need not be unit; 0 for a zero or
    /// non-finite vector).
    [[nodiscard]] glm::vec3 radiance(const glm::vec3& towards_sky) const;

    struct Sample {
        glm::vec3 direction{0.0f, 1.0f, 0.0f};  ///< unit, towards the sky
        glm::vec3 radiance{0.0f};
        double pdf = 0.0;  ///< per steradian; 0: the sky is black
    };
    /// A direction chosen in proportion to radiance (channels summed) times solid angle:
    /// u.x picks the cell and, rescaled, joins u.y to place the direction within it.
    [[nodiscard]] Sample sample(const glm::dvec2& u) const;
    /// The density per steradian with which sample() picks `towards_sky`.
    [[nodiscard]] double pdf(const glm::vec3& towards_sky) const;

    /// The radiance integrated over the sphere, W/m^2 per channel: the irradiance a sphere's
    /// cross-section receives, so pi R^2 times it is the flux the sky sends into a sphere of
    /// radius R.
    [[nodiscard]] glm::dvec3 integral() const { return integral_; }
    [[nodiscard]] bool black() const { return !(total_weight_ > 0.0); }

    [[nodiscard]] int width() const { return width_; }
    [[nodiscard]] int height() const { return height_; }
    [[nodiscard]] const std::vector<glm::vec3>& cells() const { return cells_; }

    bool operator==(const SkyRadiance& other) const {
        return width_ == other.width_ && height_ == other.height_ && cells_ == other.cells_;
    }

  private:
    /// The cell holding a unit direction.
    [[nodiscard]] std::size_t cell_of(const glm::vec3& unit) const;
    [[nodiscard]] double solid_angle(int row) const;

    int width_ = 1;
    int height_ = 1;
    std::vector<glm::vec3> cells_;
    std::vector<double> cdf_;  // per cell: cumulative radiance x solid angle, normalised
    double total_weight_ = 0.0;
    glm::dvec3 integral_{0.0};
};

/// A clear daylight sky after Preetham, Shirley and Smits ("A practical analytic model for
/// daylight", SIGGRAPH 1999): the Perez distribution of luminance and chromaticity for a sun in
/// direction `towards_sun` (from the ground towards the sun; a sun below the horizon is taken at
/// it) and atmospheric `turbidity` (2: very clear, 10: hazy; clamped to [1.7, 10]), baked into
/// a 128 x 64 grid. The sun's own disc is not in it: it stays a DirectionalLight. The model's
/// absolute luminance is scaled so that the sky gives a horizontal surface
/// `horizontal_irradiance` W/m^2 (in luminance: a coloured sky keeps that much light); below
/// the horizon it is black.
[[nodiscard]] SkyRadiance daylight_sky(const glm::vec3& towards_sun, float turbidity,
                                       float horizontal_irradiance);

/// The irradiance per channel, W/m^2, that the part of `sky` above the horizon gives an
/// upward face: the sum over the rows wholly above it of each cell's radiance times its
/// integral of cos(theta) over its solid angle (exact for the constant cells).
[[nodiscard]] glm::dvec3 horizontal_irradiance(const SkyRadiance& sky);

/// `sky` with every row wholly below the horizon replaced by a flat diffuse ground of `albedo`
/// (each channel in [0, 1]) lit by the sky above and by `sun_on_ground` (W/m^2 on the ground: a
/// sun's irradiance times the sine of its elevation): radiance albedo (E_sky + E_sun) / pi. It
/// stands in for the world outside a level's windows, so a view or a gather ray that looks down
/// through an opening sees the ground's light instead of black. A row across the horizon (an
/// odd number of rows) keeps its radiance.
[[nodiscard]] SkyRadiance with_ground(const SkyRadiance& sky, const glm::vec3& albedo,
                                      const glm::vec3& sun_on_ground);

}  // namespace luxel::lighting
