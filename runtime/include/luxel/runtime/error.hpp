#pragma once

#include <stdexcept>
#include <string>

namespace luxel {

/// Base of every error a user can cause (bad file, bad flag, missing driver). Programs catch it
/// at the top, print what() and exit non-zero; what() always names the thing that was wrong.
class Error : public std::runtime_error {
  public:
    explicit Error(const std::string& message) : std::runtime_error(message) {}
};

/// A mistake on the command line (unknown flag, bad value, missing argument, flags that
/// contradict each other), as opposed to a failure while running: tools exit 2 for it, 1 for
/// every other Error (luxel/runtime/tool_main.hpp). what() names the flag.
class UsageError : public Error {
  public:
    using Error::Error;
};

}  // namespace luxel
