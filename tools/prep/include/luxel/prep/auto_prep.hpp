#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "luxel/prep/options.hpp"
#include "luxel/runtime/jobs.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/scene/level_check.hpp"
#include "luxel/scene/scene.hpp"

/// Loading a level to play it (luxel-sandbox, luxel-ref, luxel-bench): the level is checked
/// (scene/level_check.hpp's warnings), and one that luxel-prep never prepared is prepared in
/// memory with luxel-prep's pipeline at its default options, the result kept in a cache folder
/// under the hash of the level's bytes so the next load reads it instead.
namespace luxel::prep {

struct AutoPrepSettings {
    /// Prepare an unprepared level at load; false (--no-auto-prep) makes it an error that
    /// gives the luxel-prep command to run.
    bool enabled = true;
    /// Where prepared levels are kept; empty: default_cache_dir().
    std::filesystem::path cache_dir;
};

/// $LUXEL_CACHE_DIR, else $XDG_CACHE_HOME/luxel, else $HOME/.cache/luxel; empty when none of
/// them is set (prepared levels then live in memory only).
[[nodiscard]] std::filesystem::path default_cache_dir();

/// --no-auto-prep and --prep-cache DIR, into `settings`.
void add_auto_prep_flags(CLI::App& app, AutoPrepSettings& settings);

/// The cache's name for the prepared level: 16 hex digits of a 64-bit FNV-1a hash over
/// luxel-prep's options and the bytes of the level file and of every file it reads (buffers,
/// images), so editing any of them prepares the level afresh.
[[nodiscard]] std::string content_key(const std::filesystem::path& file, const scene::Scene& level,
                                      const PrepOptions& options);

/// luxel-prep's defaults within the loaders' limits (what `luxel-prep IN -o OUT --limit ...`
/// would use).
[[nodiscard]] PrepOptions options_within(const scene::LoadOptions& limits);

/// What load_playable needs besides the file.
struct PlayableLevel {
    scene::LoadOptions limits;
    scene::LevelCheckOptions check;
    AutoPrepSettings prep;
};

/// Loads `file`, warns once about what it lacks in scene::check_level's words, and prepares it
/// when luxel-prep never did: from the cache, or with prepare() (progress on the terminal)
/// and then into the cache. A level prepare() refuses (over a limit) runs unprepared, with a
/// warning that says why. Throws luxel::Error giving the luxel-prep command when the level is
/// unprepared and `level.prep.enabled` is false. The scene names `file` (Scene::source).
[[nodiscard]] std::shared_ptr<const scene::Scene> load_playable(const std::filesystem::path& file,
                                                                const PlayableLevel& level,
                                                                JobSystem& jobs);

}  // namespace luxel::prep
