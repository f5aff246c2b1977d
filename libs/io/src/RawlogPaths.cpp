#include <lodestone/io/RawlogPaths.h>

namespace lodestone::io {

namespace {
bool endsWith(const std::string& s, const std::string& suffix) {
    return s.size() > suffix.size() &&
           s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}
}  // namespace

std::string rawlogStem(const std::string& rawlogPath) {
    std::string stem = rawlogPath;
    for (const std::string ext : {".gz", ".rawlog"}) {
        if (endsWith(stem, ext)) stem.resize(stem.size() - ext.size());
    }
    return stem;
}

bool isGzipPath(const std::string& path) { return endsWith(path, ".gz"); }

}  // namespace lodestone::io
