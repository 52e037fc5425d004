#pragma once

#include <CLI/CLI.hpp>

#include "luxel/scene/gltf.hpp"

namespace luxel::cli {

/// --limit NAME=N (repeatable): raises or lowers one of the loader's limits on what a level
/// may hold (scene::load_limits(), docs/LEVELS.md). The flag every tool that loads a level
/// takes; the rest of the shared command line is runtime/cli.hpp.
CLI::Option* add_load_limits(CLI::App& app, scene::LoadOptions& limits);

}  // namespace luxel::cli
