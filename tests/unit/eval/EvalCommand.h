#pragma once
// lodestone-eval run in-process, as the tests of its subcommands call it.
#include <EvalApp.h>

#include <sstream>
#include <string>
#include <vector>

namespace lodestone::test {

/** Runs `lodestone-eval ARGS...`; its standard output and error into `out` and `err`. */
inline int evalCmd(std::vector<std::string> args, std::string& out, std::string& err) {
    args.insert(args.begin(), "lodestone-eval");
    std::vector<const char*> argv;
    for (const auto& a : args) argv.push_back(a.c_str());
    std::ostringstream o, e;
    const int code = eval::runEvalApp(static_cast<int>(argv.size()), argv.data(), o, e);
    out = o.str();
    err = e.str();
    return code;
}

}  // namespace lodestone::test
