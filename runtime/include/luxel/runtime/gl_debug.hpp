#pragma once

namespace luxel::gl {

/// Routes KHR_debug messages of the current (debug) context to the log: high severity as error,
/// medium as warn, low as debug. Returns false when the context is not a debug context.
bool enable_debug_output();

}  // namespace luxel::gl
