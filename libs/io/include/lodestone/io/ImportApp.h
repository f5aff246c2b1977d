#pragma once

#include <ostream>

namespace lodestone::io {

/** The `lodestone-import` command line. Subcommands:
 *   tum DIR OUT.rawlog [--intrinsics fr1|fr2|fr3|default|fx,fy,cx,cy] [--max-dt S]
 * (magnetometer recordings join with the magnetic issue). Exit codes: 0 ok, 1 bad input,
 * 2 usage. */
int runImportApp(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

}  // namespace lodestone::io
