#pragma once

#include <string>

#include "luxel/runtime/error.hpp"

namespace luxel::testing {

/// The message of the luxel::Error `call` throws ("" when it throws none): for tests that check
/// an error's words.
template <typename Call>
std::string error_of(Call call) {
    try {
        call();
    } catch (const luxel::Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace luxel::testing
