#include <lodestone/io/RawlogPaths.h>

#include <filesystem>
#include <stdexcept>

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

void refuseOutputOverInput(const std::string& output, const std::vector<std::string>& inputs) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (!fs::exists(output, ec)) return;  // a new file cannot be an input
    for (const auto& input : inputs) {
        if (fs::equivalent(output, input, ec) && !ec) {
            throw std::invalid_argument("output '" + output + "' is the input '" + input +
                                        "': refusing to overwrite it");
        }
    }
}

void prepareOutputFile(const std::string& path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw std::runtime_error("output '" + path + "' is a folder");
    const fs::path parent = fs::path(path).parent_path();
    if (!parent.empty() && !fs::is_directory(parent, ec)) {
        fs::create_directories(parent, ec);
        if (ec || !fs::is_directory(parent)) {
            throw std::runtime_error("cannot create the folder of output '" + path + "': " +
                                     (ec ? ec.message() : "not a folder"));
        }
    }
}

std::string partialPath(const std::string& path) { return path + ".partial"; }

void commitPartial(const std::string& path) {
    std::error_code ec;
    std::filesystem::rename(partialPath(path), path, ec);
    if (ec) {
        throw std::runtime_error("cannot rename '" + partialPath(path) + "' to '" + path + "': " + ec.message());
    }
}

}  // namespace lodestone::io
