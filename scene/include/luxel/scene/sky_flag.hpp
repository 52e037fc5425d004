#pragma once

#include <optional>

#include <CLI/CLI.hpp>

#include "luxel/scene/sky.hpp"

namespace luxel::cli {

/// --sky none | uniform:R,G,B | daylight[:E[,T]] | FILE.exr: the sky instead of the level's own
/// (scene::parse_sky, docs/LEVELS.md "Sky"). luxel-sandbox, luxel-ref and luxel-bench take it.
CLI::Option* add_sky(CLI::App& app, std::optional<scene::SkySpec>& sky);

}  // namespace luxel::cli
