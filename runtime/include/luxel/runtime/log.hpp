#pragma once

#include <sstream>
#include <string>
#include <string_view>
#include <utility>

/// Leveled logging to stderr. Thread-safe: each message is written as one line under a lock.
/// The initial level comes from the LUXEL_LOG environment variable (trace, debug, info, warn,
/// error, off), default info.
namespace luxel::log {

enum class Level { Trace = 0, Debug, Info, Warn, Error, Off };

void set_level(Level level);
[[nodiscard]] Level level();
[[nodiscard]] bool enabled(Level level);

/// Parses a level name; throws luxel::Error naming the bad value and the valid ones.
[[nodiscard]] Level parse_level(std::string_view name);
[[nodiscard]] std::string_view level_name(Level level);

/// Writes one already formatted line.
void write(Level level, std::string_view message);

/// Streams the arguments into one line, only if the level is enabled (no formatting cost
/// otherwise).
template <class... Args>
void message(Level at, Args&&... args) {
    if (!enabled(at)) {
        return;
    }
    std::ostringstream line;
    (line << ... << std::forward<Args>(args));
    write(at, line.str());
}

template <class... Args>
void trace(Args&&... args) {
    message(Level::Trace, std::forward<Args>(args)...);
}
template <class... Args>
void debug(Args&&... args) {
    message(Level::Debug, std::forward<Args>(args)...);
}
template <class... Args>
void info(Args&&... args) {
    message(Level::Info, std::forward<Args>(args)...);
}
template <class... Args>
void warn(Args&&... args) {
    message(Level::Warn, std::forward<Args>(args)...);
}
template <class... Args>
void error(Args&&... args) {
    message(Level::Error, std::forward<Args>(args)...);
}

}  // namespace luxel::log
