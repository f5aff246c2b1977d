#pragma once

// Runs MRPT's stock command-line tools (from Debian's mrpt-apps) for comparisons.

#include <cstdio>
#include <map>
#include <regex>
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

inline bool haveRawlogEdit() { return runCommand("command -v rawlog-edit").exitCode == 0; }

/** What `rawlog-edit --info` says: the object count and occurrences per sensor label. */
struct RawlogEditInfo {
    long objects{-1};
    std::map<std::string, long> occurrences;
};

inline RawlogEditInfo rawlogEditInfo(const std::string& path) {
    RawlogEditInfo info;
    const auto r = runCommand("rawlog-edit --info -i '" + path + "'");
    std::istringstream in(r.output);
    const std::regex objects(R"(Overall number of objects\s*:\s*(\d+))");
    const std::regex sensor(R"(Sensor \(Label/Occurs/Rate/Durat\.\)\s*:\s*(.*?)\s*/\s*(\d+)\s*/)");
    for (std::string line; std::getline(in, line);) {
        std::smatch m;
        if (std::regex_search(line, m, objects)) info.objects = std::stol(m[1]);
        if (std::regex_search(line, m, sensor)) info.occurrences[m[1]] = std::stol(m[2]);
    }
    return info;
}

}  // namespace lodestone::test
