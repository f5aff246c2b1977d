// What the benches that read a run's report.json share: the file's text, and a number after a
// key (the first occurrence from where the text starts: pass a slice to look in one part).
#pragma once

#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

inline std::string slurp(const std::string& path) {
    std::ifstream in(path);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

/** The number after `"key": ` in `text`; NaN when there is none. */
inline double numberIn(const std::string& text, const std::string& key) {
    std::smatch m;
    if (!std::regex_search(text, m, std::regex("\"" + key + "\": (-?[0-9.eE+-]+)"))) return NAN;
    return std::stod(m[1]);
}
