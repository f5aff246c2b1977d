#pragma once

#include <mrpt/3rdparty/tclap/CmdLine.h>

#include <string>
#include <vector>

namespace lodestone::config {

/** How parsing a command line went. */
struct ParseOutcome {
    enum class Kind { Run, HelpShown, UsageError } kind;
    std::string error;  ///< for UsageError: which argument and what is wrong
};

/** Parses `words` (program name first) with MRPT's TCLAP, which on its own answers both --help
 * and a bad argument with `false` and prints the error itself: this tells them apart and hands
 * the error back, so the app can word it and exit with the usage code. */
ParseOutcome parseCommandLine(TCLAP::CmdLine& cmd, const std::vector<std::string>& words);

}  // namespace lodestone::config
