#pragma once

namespace luxel::detail {

/// Sanitizer builds only (a no-op otherwise): keeps the GL driver's shared objects mapped until
/// the process exits. Mesa unloads its driver when the last display is terminated; allocations
/// it keeps for the process lifetime would then be reported by LeakSanitizer against an
/// "<unknown module>", which tests/support/lsan.supp cannot name. Pinned, they are attributed to
/// the driver library and suppressed there, while leaks in luxel's own code still fail tests.
void pin_gl_driver_modules();

}  // namespace luxel::detail
