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

}  // namespace luxel
