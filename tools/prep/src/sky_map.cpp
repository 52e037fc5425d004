#include "luxel/prep/sky_map.hpp"

#include <string>
#include <system_error>

#include "luxel/runtime/error.hpp"
#include "luxel/runtime/pending_file.hpp"

namespace luxel::prep {

std::filesystem::path place_sky_map(const std::filesystem::path& map,
                                    const std::filesystem::path& output) {
    std::error_code error;
    const std::filesystem::path folder =
        std::filesystem::absolute(output, error).lexically_normal().parent_path();
    // Compared as real paths: the map's is one (the loader resolved it), and a folder reached
    // through a link holds the map as well as its real self does.
    const std::filesystem::path real_folder = std::filesystem::canonical(folder, error);
    if (!error) {
        const std::filesystem::path inside = map.lexically_relative(real_folder);
        if (!inside.empty() && *inside.begin() != "..") {
            return inside;
        }
    }
    const std::filesystem::path name = output.stem().string() + ".sky.exr";
    const std::filesystem::path copy = folder / name;
    PendingFile pending(copy);
    std::filesystem::copy_file(map, pending.path(),
                               std::filesystem::copy_options::overwrite_existing, error);
    if (error) {
        throw Error("cannot copy the sky map " + map.string() + " to " + copy.string() + ": " +
                    error.message());
    }
    pending.commit();
    return name;
}

}  // namespace luxel::prep
