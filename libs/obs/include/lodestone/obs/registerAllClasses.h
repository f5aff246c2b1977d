#pragma once

namespace lodestone {

/** Registers every MRPT-serializable class of Lodestone with MRPT's class registry, so that
 * rawlogs holding them can be read. Every app calls it first; it is cheap and idempotent.
 * (An MRPT_INITIALIZER in a library can be dropped by the linker, hence an explicit call.) */
void registerAllClasses();

}  // namespace lodestone
