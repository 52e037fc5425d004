#pragma once

#include <array>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "luxel/ecs/registry.hpp"

namespace luxel::ecs {

/// The phases of a frame, run in this order. Each exists so that systems agree on what has
/// happened before them:
enum class Phase : std::uint8_t {
    Input,       ///< read devices and network; write intent components
    Simulation,  ///< gameplay, animation, physics: move Transforms
    Transforms,  ///< the TransformSystem: Transform -> WorldTransform
    Lighting,    ///< read what moved (observers of WorldTransform, lights...), schedule GI work
    Render,      ///< draw from the settled state
};

inline constexpr std::array<Phase, 5> all_phases{Phase::Input, Phase::Simulation, Phase::Transforms,
                                                 Phase::Lighting, Phase::Render};

/// "input", "simulation", "transforms", "lighting", "render".
[[nodiscard]] std::string_view to_string(Phase phase) noexcept;

/// An explicit, ordered list of systems: phases in Phase order, and within a phase the order in
/// which systems were added. No global state: a pipeline runs whichever registry it is given, so
/// one pipeline can drive several registries and several pipelines can coexist.
///
///     Pipeline pipeline;
///     pipeline.add(Phase::Simulation, "spin", [](Registry& r, double dt) { ... });
///     pipeline.add(Phase::Transforms, "transforms",
///                  [&transforms](Registry& r, double) { transforms.update(r); });
///     pipeline.run(registry, 1.0 / 60.0);
///
/// A system is any callable taking (Registry&, double dt_seconds) or (Registry&). Names are
/// unique within a pipeline, for remove/set_enabled and for diagnostics. The system list may not
/// be changed while run() is running (EcsError); a system's exception leaves run() with the
/// remaining systems of that frame not run.
class Pipeline {
  public:
    using System = std::function<void(Registry&, double)>;

    /// Appends a system to a phase. Throws EcsError if the name is taken (or empty).
    template <class Fn>
    requires std::invocable<Fn&, Registry&, double> || std::invocable<Fn&, Registry&>
    void add(Phase phase, std::string name, Fn&& fn) {
        if constexpr (std::invocable<Fn&, Registry&, double>) {
            add_system(phase, std::move(name), System(std::forward<Fn>(fn)));
        } else {
            add_system(phase, std::move(name),
                       System([inner = std::forward<Fn>(fn)](Registry& registry, double) mutable {
                           inner(registry);
                       }));
        }
    }

    /// Removes the named system; returns whether it existed.
    bool remove(std::string_view name);
    /// Skips (false) or resumes (true) the named system without losing its place. Throws
    /// EcsError for an unknown name.
    void set_enabled(std::string_view name, bool enabled);
    [[nodiscard]] bool contains(std::string_view name) const noexcept;

    /// Runs every enabled system once, phase by phase, in order. Counts the frame.
    void run(Registry& registry, double dt_seconds);

    /// "phase/name" of every system in run order (disabled ones included): what run() will do.
    [[nodiscard]] std::vector<std::string> describe() const;
    /// Number of completed run() calls.
    [[nodiscard]] std::uint64_t frames_run() const noexcept { return frames_run_; }

  private:
    struct Entry {
        std::string name;
        System system;
        bool enabled = true;
    };

    void add_system(Phase phase, std::string name, System system);
    void check_not_running(std::string_view operation) const;
    Entry* find(std::string_view name) noexcept;

    std::array<std::vector<Entry>, all_phases.size()> phases_;
    std::uint64_t frames_run_ = 0;
    bool running_ = false;
};

}  // namespace luxel::ecs
