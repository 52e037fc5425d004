#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace luxel::lighting {

/// The kinds of lighting work the Scheduler spreads across frames (docs/METHOD.md §1.2-1.3).
enum class WorkKind : std::uint8_t {
    PhotonProbe,   ///< one photon per group, round robin
    GroupRetrace,  ///< retrace of one invalidated photon group
    CausticSlice,  ///< photons of one caustic slice (size = thousands of photons)
    AimRebuild,    ///< rebuild of one surface's approximated illumination map
    IimGather,     ///< a batch of IIM texel gathers (size = texels)
    ProbeGather,   ///< a pass of a few irradiance probes (size = probes)
};
// (The IIM's fade between its two buffers is a mix in the shader over time, not work the
// scheduler runs: there is no blend kind.)
inline constexpr std::size_t kWorkKindCount = 6;

/// "photon_probe", "group_retrace", ...: stable names for the HUD, logs and luxel-bench.
[[nodiscard]] std::string_view name(WorkKind kind);
/// The kind's index into per-kind arrays (0 .. kWorkKindCount-1).
[[nodiscard]] constexpr std::size_t index(WorkKind kind) {
    return static_cast<std::size_t>(kind);
}

/// Per-kind values, indexed by index(WorkKind).
template <typename T>
using PerKind = std::array<T, kWorkKindCount>;

struct CostModelSettings {
    /// Priors, in ms per unit of size, used until measurements replace them. They are guesses
    /// of the order of magnitude on a desktop CPU, not measurements: probe, retrace, caustic
    /// part (per 1,000 photons), AIM rebuild, IIM gather (per texel batch unit), irradiance
    /// probe (per probe).
    PerKind<double> prior_ms = {0.05, 0.2, 0.5, 1.0, 0.05, 0.3};
    /// How many measurements the prior counts as. 0 (the default): the first measurement
    /// replaces it, since a prior is a guess and may be off by 10x on another machine or
    /// scene. Then the first measurements are averaged evenly (weight 1/(prior_weight + n + 1))
    /// until that weight falls to `smoothing`.
    double prior_weight = 0.0;
    /// Weight of the newest sample once the history is long: an exponentially weighted mean
    /// whose memory is about 1/smoothing samples, so the model follows a scene that gets heavier.
    double smoothing = 0.1;
    /// The mean absolute deviation assumed before any measurement, and right after the first
    /// one, as a fraction of the mean: a barely measured kind must not claim to be predictable.
    double prior_relative_deviation = 0.5;
    /// prediction_error() = error_factor * mean absolute deviation. For a uniform or normal
    /// spread of costs, 3 deviations cover every sample or nearly so.
    double error_factor = 3.0;
    /// Floor of the error bound relative to the mean: a perfectly steady kind still jitters.
    double min_relative_error = 0.05;
    /// Absolute floor of the error bound per unit (timer resolution, cache effects).
    double min_error_ms = 0.001;
};

/// What the model knows of one kind (for the HUD and tests).
struct KindCost {
    double mean_ms = 0.0;       ///< per unit of size
    double deviation_ms = 0.0;  ///< weighted mean absolute deviation of the prediction, per unit
    std::uint64_t samples = 0;  ///< measurements taken into account
};

/// The cost of each kind of work unit, learned from measured durations, starting from a prior.
/// The model is per unit of size (a gather batch of 64 texels costs 64x one texel): a unit's
/// prediction is mean * size. Non-finite or negative samples and sizes are ignored, so one bad
/// timer reading cannot poison the scheduler.
class CostModel {
  public:
    explicit CostModel(CostModelSettings settings = {});

    /// Feeds one measured duration of a unit of `kind` and `size`.
    void record(WorkKind kind, double size, double measured_ms);

    /// Predicted duration of a unit (ms): the learned mean per unit times size; 0 for size <= 0.
    [[nodiscard]] double predict(WorkKind kind, double size) const;
    /// How far the actual duration may be from predict() (ms): a bound from the weighted mean
    /// absolute deviation of past predictions, never below the floors of the settings.
    [[nodiscard]] double prediction_error(WorkKind kind, double size) const;

    [[nodiscard]] const KindCost& cost(WorkKind kind) const { return costs_[index(kind)]; }
    [[nodiscard]] const CostModelSettings& settings() const { return settings_; }
    /// Forgets the measurements of every kind: back to the priors.
    void reset();

  private:
    CostModelSettings settings_;
    PerKind<KindCost> costs_{};
};

}  // namespace luxel::lighting
