#pragma once

// Drivers whose destruction would end the process (a throwing destructor, a hang) are kept
// alive, never destroyed: recorded here so they stay reachable (and LeakSanitizer agrees they
// are not leaks) until the process ends.

namespace lodestone::drivers::detail {

void abandon(const void* driver);

}  // namespace lodestone::drivers::detail
