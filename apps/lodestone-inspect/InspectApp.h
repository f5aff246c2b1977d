#pragma once

#include <ostream>

namespace lodestone::inspect {

/** Exit codes of lodestone-inspect. */
enum ExitCode : int { kExitOk = 0, kExitBadInput = 1, kExitUsage = 2 };

/** The whole `lodestone-inspect` command line: summary, list, show, export, to-imu.
 * `argv[0]` is the program name. Results go to `out`, errors to `err`; returns an ExitCode.
 * Nothing is thrown: bad input is reported with the file, entry or key it concerns. */
int runInspectApp(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

}  // namespace lodestone::inspect
