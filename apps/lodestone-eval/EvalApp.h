#pragma once

#include <ostream>

namespace lodestone::eval {

/** The `lodestone-eval EST.tum GT.tum [--plot OUT.png] [--max-dt S]` command line: ATE and RPE
 * (per second and per metre) as the TUM RGB-D benchmark defines them, and a picture. Exit codes:
 * 0 ok, 1 bad input, 2 usage. */
int runEvalApp(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

}  // namespace lodestone::eval
