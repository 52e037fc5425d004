#include "luxel/scene/load_limits_flag.hpp"

#include <string>
#include <vector>

#include "luxel/runtime/error.hpp"

namespace luxel::cli {

CLI::Option* add_load_limits(CLI::App& app, scene::LoadOptions& limits) {
    std::string names;
    for (const scene::LoadLimit& limit : scene::load_limits()) {
        names += (names.empty() ? "" : ", ") + std::string(limit.name);
    }
    return app
        .add_option_function<std::vector<std::string>>(
            "--limit",
            [&limits](const std::vector<std::string>& assignments) {
                for (const std::string& assignment : assignments) {
                    try {
                        scene::set_load_limit(limits, assignment);
                    } catch (const Error& e) {
                        throw CLI::ValidationError("--limit", e.what());
                    }
                }
            },
            "NAME=N: a limit on what a level may hold (" + names + "; docs/LEVELS.md); repeatable")
        ->expected(1)
        ->take_all();
}

}  // namespace luxel::cli
