#pragma once

#include <ostream>

namespace lodestone::grab {

/** `lodestone-grab GRAB.ini [--out PREFIX] [--duration S] [--plugin LIB]... [--quiet]`.
 * SIGINT / SIGTERM end the grab cleanly (a second one kills). Exit codes: 0 ok, 1 bad input or
 * a sensor that failed, 2 usage. */
int runGrabApp(int argc, const char* const* argv, std::ostream& out, std::ostream& err,
               bool terminal);

}  // namespace lodestone::grab
