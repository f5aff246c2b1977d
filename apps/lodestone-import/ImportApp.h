#pragma once

#include <ostream>

namespace lodestone::datasets {

/** The `lodestone-import` command line. Subcommands:
 *   tum DIR OUT.rawlog [--intrinsics fr1|fr2|fr3|default|fx,fy,cx,cy] [--max-dt S]
 *   aalto DIR TRIAL OUT.rawlog, kok FILE.csv OUT.rawlog [--seed --bias --sp2 --sh2
 * --odometry-rate]. Exit codes: 0 ok, 1 bad input, 2 usage. */
int runImportApp(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

}  // namespace lodestone::datasets
