#pragma once

#include <ostream>

namespace lodestone::slamapp {

/** The `lodestone-slam (--rawlog FILE | --sim SCENARIO.ini) --config INI --out DIR
 * [--ground-truth GT.tum] [--max-seconds S] [--quiet]` command line. Exit codes: 0 ok, 1 bad
 * input or a fault in the data (outputs of what was processed are written), 2 usage. */
int runSlamApp(int argc, const char* const* argv, std::ostream& out, std::ostream& err,
               bool terminal);

}  // namespace lodestone::slamapp
