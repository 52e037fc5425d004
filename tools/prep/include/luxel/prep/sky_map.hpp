#pragma once

#include <filesystem>

namespace luxel::prep {

/// Where a prepared level written to `output` finds the sky map `map` (the map's real path, as
/// the loader resolved it in the source level's folder): a level names its map relative to its
/// own folder and may read nothing outside it (docs/LEVELS.md, "Files a level may read"). A map
/// already inside `output`'s folder is named where it is; any other is copied beside `output`
/// as `<output's stem>.sky.exr` (atomically) and named so. Returns the name relative to
/// `output`'s folder. Throws luxel::Error naming both files when the copy fails.
[[nodiscard]] std::filesystem::path place_sky_map(const std::filesystem::path& map,
                                                  const std::filesystem::path& output);

}  // namespace luxel::prep
