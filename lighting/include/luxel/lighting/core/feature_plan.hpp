#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace luxel::lighting {

/// What the scene holds this frame, counted by the LightingSystem from its component mirrors
/// (never by scanning the registry). Plain data, so a plan can be computed and tested anywhere.
struct SceneCensus {
    std::uint32_t lights_enabled = 0;
    std::uint32_t lights_total = 0;  ///< enabled or not
    std::uint32_t caustic_generators = 0;
    std::uint32_t lightmapped_surfaces = 0;
    /// Mesh objects with no light-mapped surface: what the irradiance probes light.
    std::uint32_t unmapped_receivers = 0;
    std::uint32_t dynamic_objects = 0;  ///< entities that may move (Dynamic mesh instances)
    std::uint32_t moving_objects = 0;   ///< of those, the ones that moved this frame
    std::uint32_t specular_materials = 0;
    /// Static geometry added or removed this frame: the photons it affects are found by probes.
    std::uint32_t geometry_changes = 0;
    /// AIM rebuilds or IIM gathers requested: with no light enabled, what the maps still hold
    /// of the lights switched off must be cleared (the passes stay on until it is).
    bool maps_pending = false;
    /// Irradiance probes wait for a pass (IrradianceProbes::pending).
    bool probes_pending = false;
    /// Nothing pending in the scheduler and every delta (delta_f, delta_i) under its threshold.
    bool converged = false;

    bool operator==(const SceneCensus&) const = default;
};

/// The passes and the per-frame work they imply (docs/METHOD.md §1.3).
enum class Pass : std::uint8_t {
    PhotonTracing,     ///< global photons: group retraces (and the photon map they feed)
    SelectiveProbes,   ///< probe photons that find the groups a change invalidated
    Caustics,          ///< caustic photon slices (tracing)
    Aim,               ///< AIM rebuilds
    IimGather,         ///< IIM texel gathers
    Shadows,           ///< shadow maps (render)
    Direct,            ///< direct lighting (render)
    Specular,          ///< the specular term: reflection and refraction (render)
    CausticFilter,     ///< caustic buffers and their filter/composite pass (render)
    IrradianceProbes,  ///< probes gathered (when pending) and interpolated for unmapped receivers
};
inline constexpr std::size_t kPassCount = 10;

/// "photon_tracing", "selective_probes", ...
[[nodiscard]] std::string_view name(Pass pass);

/// Which passes exist this frame, and why. Rules, checked in this order for each pass:
///
/// - No enabled light: no lighting work at all (every pass off).
/// - No light-mapped surface: no global photons (nowhere to store them), no AIM, no IIM.
/// - No caustic generator: no caustic photons, no caustic buffers, no caustic filter pass.
/// - No specular material: no reflection pass.
/// - Converged and nothing moving this frame (a static scene, or one whose dynamic objects are
///   at rest): no tracing, no probing, no gathering, no blending; only the render passes stay
///   (shadows, direct, the specular term, the caustic filter over the caustics already traced).
/// - Probes only where something can invalidate groups behind our back: dynamic objects or
///   static geometry edits. Light changes invalidate their own groups without probes.
/// - Irradiance probes only for a lit scene with light-mapped surfaces (the AIM they gather
///   from) and receivers that have no light map (what they light).
///
/// from() is cheap and deterministic: call it every frame and compare with changed_from() to
/// allocate or free what a pass needs when it turns on or off.
class FeaturePlan {
  public:
    /// The plan of an empty scene: everything off.
    FeaturePlan() : FeaturePlan(SceneCensus{}) {}
    explicit FeaturePlan(const SceneCensus& census);
    [[nodiscard]] static FeaturePlan from(const SceneCensus& census) { return FeaturePlan(census); }

    [[nodiscard]] bool enabled(Pass pass) const { return on_[static_cast<std::size_t>(pass)]; }
    /// One line: why the pass is on or off.
    [[nodiscard]] std::string reason(Pass pass) const;
    /// A table, one pass a line: name, on/off, reason.
    [[nodiscard]] std::string describe() const;
    /// Passes that are on in one plan and off in the other.
    [[nodiscard]] std::vector<Pass> changed_from(const FeaturePlan& previous) const;
    /// Passes on.
    [[nodiscard]] std::size_t active_count() const;
    [[nodiscard]] const SceneCensus& census() const { return census_; }

    [[nodiscard]] bool photon_tracing() const { return enabled(Pass::PhotonTracing); }
    [[nodiscard]] bool selective_probes() const { return enabled(Pass::SelectiveProbes); }
    [[nodiscard]] bool caustics() const { return enabled(Pass::Caustics); }
    [[nodiscard]] bool aim() const { return enabled(Pass::Aim); }
    [[nodiscard]] bool iim_gather() const { return enabled(Pass::IimGather); }
    [[nodiscard]] bool shadows() const { return enabled(Pass::Shadows); }
    [[nodiscard]] bool direct() const { return enabled(Pass::Direct); }
    [[nodiscard]] bool specular() const { return enabled(Pass::Specular); }
    [[nodiscard]] bool caustic_filter() const { return enabled(Pass::CausticFilter); }
    [[nodiscard]] bool irradiance_probes() const { return enabled(Pass::IrradianceProbes); }
    /// Caustic photon lists and buffers exist (whether or not they are retraced this frame).
    [[nodiscard]] bool caustic_data() const { return caustic_filter(); }
    /// Anything traced or gathered this frame: false means the scheduler gets no lighting work.
    [[nodiscard]] bool any_tracing() const {
        return photon_tracing() || selective_probes() || caustics() || aim() || iim_gather();
    }

    bool operator==(const FeaturePlan&) const = default;

  private:
    SceneCensus census_;
    std::array<bool, kPassCount> on_{};
    std::array<std::string, kPassCount> reasons_{};
};

}  // namespace luxel::lighting
