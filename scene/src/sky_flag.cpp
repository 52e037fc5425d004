#include "luxel/scene/sky_flag.hpp"

#include <string>

#include "luxel/runtime/error.hpp"

namespace luxel::cli {

CLI::Option* add_sky(CLI::App& app, std::optional<scene::SkySpec>& sky) {
    return app.add_option_function<std::string>(
        "--sky",
        [&sky](const std::string& text) {
            try {
                sky = scene::parse_sky(text);
            } catch (const Error& e) {
                throw CLI::ValidationError("--sky", e.what());
            }
        },
        "the sky instead of the level's: none, uniform:R,G,B (W/(m^2 sr)), daylight[:E[,T]] "
        "(E W/m^2 on the ground from the sky, turbidity T; the sun is the level's), either "
        "with a last ,ground=A (an albedo below the horizon), or an equirectangular FILE.exr "
        "(docs/LEVELS.md)");
}

}  // namespace luxel::cli
