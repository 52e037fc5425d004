#include "luxel/runtime/log.hpp"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <string>

#include "luxel/runtime/error.hpp"

namespace luxel::log {
namespace {

Level initial_level() {
    const char* env = std::getenv("LUXEL_LOG");
    if (env == nullptr || *env == '\0') {
        return Level::Info;
    }
    try {
        return parse_level(env);
    } catch (const Error& e) {
        std::fprintf(stderr, "[luxel warn ] LUXEL_LOG ignored: %s\n", e.what());
        return Level::Info;
    }
}

std::atomic<Level>& current_level() {
    static std::atomic<Level> level{initial_level()};
    return level;
}

std::mutex& output_mutex() {
    static std::mutex mutex;
    return mutex;
}

}  // namespace

void set_level(Level new_level) {
    current_level().store(new_level);
}
Level level() {
    return current_level().load();
}
bool enabled(Level at) {
    return at != Level::Off && at >= level();
}

Level parse_level(std::string_view name) {
    for (Level candidate :
         {Level::Trace, Level::Debug, Level::Info, Level::Warn, Level::Error, Level::Off}) {
        if (name == level_name(candidate)) {
            return candidate;
        }
    }
    throw Error("unknown log level '" + std::string(name) +
                "' (expected trace, debug, info, warn, error or off)");
}

std::string_view level_name(Level at) {
    switch (at) {
        case Level::Trace:
            return "trace";
        case Level::Debug:
            return "debug";
        case Level::Info:
            return "info";
        case Level::Warn:
            return "warn";
        case Level::Error:
            return "error";
        case Level::Off:
            return "off";
    }
    return "?";
}

void write(Level at, std::string_view message) {
    if (!enabled(at)) {
        return;
    }
    const std::lock_guard lock(output_mutex());
    std::fprintf(stderr, "[luxel %-5.*s] %.*s\n", static_cast<int>(level_name(at).size()),
                 level_name(at).data(), static_cast<int>(message.size()), message.data());
}

}  // namespace luxel::log
