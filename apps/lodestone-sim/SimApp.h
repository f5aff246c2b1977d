#pragma once

#include <ostream>

namespace lodestone::sim {

/** The `lodestone-sim` command line:
 *   lodestone-sim --config SCENARIO.ini --out OUT.rawlog[.gz] [--seed N] [--plot MAP.png]
 *   lodestone-sim --config SCENARIO.ini --plot MAP.png          (the picture only)
 * Exit codes: 0 ok, 1 bad input (the INI key or file at fault is named), 2 usage. */
int runSimApp(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

}  // namespace lodestone::sim
