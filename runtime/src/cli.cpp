#include "luxel/runtime/cli.hpp"

#include <algorithm>

#include "luxel/runtime/error.hpp"
#include "luxel/runtime/log.hpp"

namespace luxel::cli {

bool parse(CLI::App& app, int argc, char** argv) {
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        (void)app.exit(e);
        return false;
    } catch (const CLI::CallForAllHelp& e) {
        (void)app.exit(e);
        return false;
    } catch (const CLI::CallForVersion& e) {
        (void)app.exit(e);
        return false;
    } catch (const CLI::ParseError& e) {
        // One line, whatever CLI11 wrapped: scripts read the first line of stderr.
        std::string message = e.what();
        std::replace(message.begin(), message.end(), '\n', ' ');
        throw UsageError(message);
    }
    return true;
}

CLI::Option* add_threads(CLI::App& app, int& threads) {
    return app.add_option("--threads", threads, "job threads (0: all cores)")
        ->check(CLI::Range(0, 1024))
        ->capture_default_str();
}

CLI::Option* add_log_level(CLI::App& app) {
    return app.add_option_function<std::string>(
        "--log-level",
        [](const std::string& name) {
            try {
                log::set_level(log::parse_level(name));
            } catch (const Error& e) {
                throw CLI::ValidationError("--log-level", e.what());
            }
        },
        "trace, debug, info, warn, error or off (default: LUXEL_LOG, else info)");
}

}  // namespace luxel::cli
