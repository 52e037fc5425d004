#include "luxel/prep/auto_prep.hpp"

#include <array>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <system_error>
#include <vector>

#include "luxel/prep/prep.hpp"
#include "luxel/runtime/clock.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/runtime/log.hpp"

namespace luxel::prep {
namespace {

/// Names what the cached files were made by: a change to luxel-prep's output format or to its
/// algorithms bumps it, and every level is prepared afresh.
constexpr const char* kCacheVersion = "luxel-prep auto 3";

/// 64-bit FNV-1a, fed in pieces.
class Fnv1a {
  public:
    void add(const void* data, std::size_t size) {
        const auto* bytes = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < size; ++i) {
            hash_ = (hash_ ^ bytes[i]) * 0x100000001b3ull;
        }
    }
    void add(const std::string& text) { add(text.data(), text.size() + 1); }  // with its NUL
    /// The file's bytes; throws luxel::Error naming it when it cannot be read.
    void add_file(const std::filesystem::path& file) {
        std::ifstream in(file, std::ios::binary);
        if (!in) {
            throw Error(file.string() + ": cannot read it to hash it");
        }
        std::array<char, 1 << 16> chunk{};
        while (in.read(chunk.data(), chunk.size()) || in.gcount() > 0) {
            add(chunk.data(), static_cast<std::size_t>(in.gcount()));
        }
    }
    [[nodiscard]] std::string hex() const {
        char text[17];
        std::snprintf(text, sizeof(text), "%016" PRIx64, hash_);
        return text;
    }

  private:
    std::uint64_t hash_ = 0xcbf29ce484222325ull;
};

std::filesystem::path env_path(const char* name) {
    const char* value = std::getenv(name);
    return value != nullptr && *value != '\0' ? std::filesystem::path(value)
                                              : std::filesystem::path();
}

/// The cached prepared level, when there is a readable one; it names `level`'s file.
std::shared_ptr<scene::Scene> from_cache(const std::filesystem::path& cached,
                                         const scene::Scene& level,
                                         const scene::LoadOptions& limits) {
    std::error_code error;
    if (cached.empty() || !std::filesystem::is_regular_file(cached, error)) {
        return nullptr;
    }
    try {
        auto prepared = std::make_shared<scene::Scene>(scene::load_gltf(cached, limits));
        if (!scene::is_prepared(*prepared)) {
            return nullptr;
        }
        prepared->source = level.source;
        // The level's sky is the level's: a map it names (resolved in its own folder) is not
        // written into the cache's copy.
        prepared->sky = level.sky;
        log::info(level.in_file("light-map layout from the cache: " + cached.string()));
        return prepared;
    } catch (const Error& e) {
        // A damaged cache file is prepared again and replaced.
        log::warn(level.in_file("ignoring the cached preparation: " + std::string(e.what())));
        return nullptr;
    }
}

/// Writes the prepared level into the cache (atomically: save_gltf goes through PendingFile);
/// the words for the log line that says where, or why not.
std::string into_cache(const scene::Scene& prepared, const std::filesystem::path& cached) {
    if (cached.empty()) {
        return "not cached (no cache folder: set LUXEL_CACHE_DIR or --prep-cache DIR)";
    }
    try {
        std::filesystem::create_directories(cached.parent_path());
        scene::save_gltf(prepared, cached);
        return "cached as " + cached.string();
    } catch (const std::exception& e) {
        return "not cached (" + std::string(e.what()) + ")";
    }
}

/// Prepares `level` (read from `file`) with luxel-prep's pipeline, from the cache or afresh;
/// null when the pipeline refuses it.
std::shared_ptr<const scene::Scene> auto_prepare(const std::filesystem::path& file,
                                                 const scene::Scene& level,
                                                 const PlayableLevel& settings, JobSystem& jobs) {
    const PrepOptions options = options_within(settings.limits);
    const std::filesystem::path folder =
        settings.prep.cache_dir.empty() ? default_cache_dir() : settings.prep.cache_dir;
    const std::filesystem::path cached =
        folder.empty() ? folder : folder / (content_key(file, level, options) + ".glb");
    if (auto prepared = from_cache(cached, level, settings.limits)) {
        return prepared;
    }
    const Stopwatch watch;
    TerminalProgress progress;
    PrepResult result;
    try {
        result = prepare(level, options, jobs, &progress);
    } catch (const Error& e) {
        progress.finish();
        log::warn(scene::not_prepared_text(level) +
                  ": luxel-prep's pipeline could not prepare it (" + e.what() +
                  "): it gets no indirect light");
        return nullptr;
    }
    progress.finish();
    result.scene.source = level.source;
    const std::string where = into_cache(result.scene, cached);
    log::info(level.in_file(
        "prepared for light maps in " + std::to_string(static_cast<long long>(watch.elapsed_ms())) +
        " ms: " + std::to_string(result.report.surfaces) + " surfaces on " +
        std::to_string(result.page_count) + (result.page_count == 1 ? " page of " : " pages of ") +
        std::to_string(result.page_size) + "x" + std::to_string(result.page_size) + " texels; " +
        where));
    return std::make_shared<const scene::Scene>(std::move(result.scene));
}

}  // namespace

std::filesystem::path default_cache_dir() {
    if (auto dir = env_path("LUXEL_CACHE_DIR"); !dir.empty()) {
        return dir;
    }
    if (auto dir = env_path("XDG_CACHE_HOME"); !dir.empty()) {
        return dir / "luxel" / "prepared";
    }
    if (auto home = env_path("HOME"); !home.empty()) {
        return home / ".cache" / "luxel" / "prepared";
    }
    return {};
}

void add_auto_prep_flags(CLI::App& app, AutoPrepSettings& settings) {
    app.add_flag_function(
        "--no-auto-prep", [&settings](std::int64_t) { settings.enabled = false; },
        "refuse a level luxel-prep has not prepared (the error gives the command) instead of "
        "preparing it at load");
    app.add_option("--prep-cache", settings.cache_dir,
                   "where levels prepared at load are kept (default $LUXEL_CACHE_DIR, else "
                   "$XDG_CACHE_HOME/luxel/prepared, else ~/.cache/luxel/prepared)");
}

std::string content_key(const std::filesystem::path& file, const scene::Scene& level,
                        const PrepOptions& options) {
    Fnv1a hash;
    hash.add(kCacheVersion);
    char text[256];
    std::snprintf(text, sizeof(text),
                  "%.17g %d %" PRIu64 " %.17g %.17g %d %d %d %.17g %.17g %d %zu %" PRIu64
                  " %" PRIu64,
                  options.texel_size, options.min_texels_across, options.texel_budget,
                  options.hidden_texel_scale, options.crease_degrees, options.padding,
                  options.page_size, options.auto_page_limit, options.surface_texel_budget,
                  options.max_stretch, options.lightmap_specular ? 1 : 0, options.max_total_texels,
                  options.max_triangles, options.max_accessors);
    hash.add(std::string(text));
    hash.add_file(file);
    for (const std::filesystem::path& external : level.report.external_files) {
        hash.add(external.filename().string());
        hash.add_file(external);
    }
    return hash.hex();
}

PrepOptions options_within(const scene::LoadOptions& limits) {
    PrepOptions options;
    options.max_total_texels = limits.max_lightmap_texels;
    options.max_triangles = limits.max_prep_triangles;
    options.max_accessors = limits.max_array_elements;
    return options;
}

std::shared_ptr<const scene::Scene> load_playable(const std::filesystem::path& file,
                                                  const PlayableLevel& settings, JobSystem& jobs) {
    auto level = std::make_shared<const scene::Scene>(scene::load_gltf(file, settings.limits));
    for (const scene::LevelDiagnosis& diagnosis : scene::check_level(*level, settings.check)) {
        if (diagnosis.problem != scene::LevelProblem::NotPrepared) {
            log::warn(diagnosis.message);
        }
    }
    if (scene::is_prepared(*level)) {
        return level;
    }
    const std::string command = scene::prep_command(level->source);
    if (!settings.prep.enabled) {
        throw Error(scene::not_prepared_text(*level) +
                    ", and --no-auto-prep refuses to prepare it at load; prepare it with: " +
                    command + ", then run that file");
    }
    log::warn(scene::not_prepared_text(*level) +
              ": preparing it in memory with luxel-prep's pipeline (to prepare it for good: " +
              command + ")");
    auto prepared = auto_prepare(file, *level, settings, jobs);
    return prepared ? prepared : level;
}

}  // namespace luxel::prep
