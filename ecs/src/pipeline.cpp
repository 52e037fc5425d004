#include "luxel/ecs/pipeline.hpp"

#include <algorithm>

namespace luxel::ecs {

std::string_view to_string(Phase phase) noexcept {
    switch (phase) {
        case Phase::Input:
            return "input";
        case Phase::Simulation:
            return "simulation";
        case Phase::Transforms:
            return "transforms";
        case Phase::Lighting:
            return "lighting";
        case Phase::Render:
            return "render";
    }
    return "unknown";
}

void Pipeline::add_system(Phase phase, std::string name, System system) {
    check_not_running("add");
    if (name.empty()) {
        throw EcsError("luxel::ecs: a pipeline system needs a name");
    }
    if (contains(name)) {
        throw EcsError("luxel::ecs: the pipeline already has a system named '" + name + "'");
    }
    phases_[static_cast<std::size_t>(phase)].push_back(Entry{std::move(name), std::move(system)});
}

bool Pipeline::remove(std::string_view name) {
    check_not_running("remove");
    for (auto& systems : phases_) {
        const auto it = std::find_if(systems.begin(), systems.end(),
                                     [name](const Entry& entry) { return entry.name == name; });
        if (it != systems.end()) {
            systems.erase(it);
            return true;
        }
    }
    return false;
}

void Pipeline::set_enabled(std::string_view name, bool enabled) {
    Entry* entry = find(name);
    if (entry == nullptr) {
        throw EcsError("luxel::ecs: the pipeline has no system named '" + std::string(name) + "'");
    }
    entry->enabled = enabled;
}

bool Pipeline::contains(std::string_view name) const noexcept {
    for (const auto& systems : phases_) {
        for (const Entry& entry : systems) {
            if (entry.name == name) {
                return true;
            }
        }
    }
    return false;
}

Pipeline::Entry* Pipeline::find(std::string_view name) noexcept {
    for (auto& systems : phases_) {
        for (Entry& entry : systems) {
            if (entry.name == name) {
                return &entry;
            }
        }
    }
    return nullptr;
}

void Pipeline::run(Registry& registry, double dt_seconds) {
    check_not_running("run");
    struct RunningScope {
        bool& running;
        explicit RunningScope(bool& flag) : running(flag) { running = true; }
        RunningScope(const RunningScope&) = delete;
        RunningScope& operator=(const RunningScope&) = delete;
        ~RunningScope() { running = false; }
    } scope(running_);
    for (auto& systems : phases_) {
        for (Entry& entry : systems) {
            if (entry.enabled) {
                entry.system(registry, dt_seconds);
            }
        }
    }
    ++frames_run_;
}

std::vector<std::string> Pipeline::describe() const {
    std::vector<std::string> lines;
    for (const Phase phase : all_phases) {
        for (const Entry& entry : phases_[static_cast<std::size_t>(phase)]) {
            lines.push_back(std::string(to_string(phase)) + "/" + entry.name +
                            (entry.enabled ? "" : " (disabled)"));
        }
    }
    return lines;
}

void Pipeline::check_not_running(std::string_view operation) const {
    if (running_) {
        throw EcsError("luxel::ecs: Pipeline::" + std::string(operation) +
                       " called while the pipeline is running");
    }
}

}  // namespace luxel::ecs
