#pragma once

// Runs MRPT's stock command-line tools (from Debian's mrpt-apps) for comparisons.

#include <cstdio>
#include <map>
#include <sstream>
#include <string>

namespace lodestone::test {

struct CommandResult {
    int exitCode{-1};
    std::string output;  // stdout and stderr together
};

inline CommandResult runCommand(const std::string& command) {
    CommandResult r;
    FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
    if (!pipe) return r;
    char buf[4096];
    while (std::fgets(buf, sizeof(buf), pipe)) r.output += buf;
    const int status = ::pclose(pipe);
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

/** What to put before a stock MRPT tool's command line when it loads our plugin: empty, or in
 * a sanitizer build the sanitizer runtimes preloaded (the tool itself is not instrumented). */
inline std::string stockToolEnv() { return LODESTONE_STOCK_TOOL_ENV; }

inline bool haveRawlogEdit() { return runCommand("command -v rawlog-edit").exitCode == 0; }

/** What `rawlog-edit --info` says: the object count and occurrences per sensor label. */
struct RawlogEditInfo {
    long objects{-1};
    std::map<std::string, long> occurrences;
};

/** `plugin`: a module rawlog-edit loads first (`-p`), e.g. Lodestone's MRPT plugin. */
inline RawlogEditInfo rawlogEditInfo(const std::string& path, const std::string& plugin = "") {
    RawlogEditInfo info;
    const std::string load = plugin.empty() ? "" : "-p '" + plugin + "' ";
    const auto r = runCommand((plugin.empty() ? std::string() : stockToolEnv()) + "rawlog-edit " +
                              load + "--info -i '" + path + "'");
    const auto trim = [](std::string s) {
        s.erase(0, s.find_first_not_of(' '));
        s.erase(s.find_last_not_of(' ') + 1);
        return s;
    };
    std::istringstream in(r.output);
    for (std::string line; std::getline(in, line);) {
        const auto colon = line.find(':');
        if (colon == std::string::npos) continue;
        const std::string key = trim(line.substr(0, colon)), value = line.substr(colon + 1);
        if (key == "Overall number of objects") info.objects = std::stol(value);
        if (key == "Sensor (Label/Occurs/Rate/Durat.)") {
            // "<label> / <occurrences> / <rate> /<duration>"
            const auto slash = value.find('/');
            info.occurrences[trim(value.substr(0, slash))] = std::stol(value.substr(slash + 1));
        }
    }
    return info;
}

}  // namespace lodestone::test
