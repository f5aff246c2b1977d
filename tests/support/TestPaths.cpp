#include "TestPaths.h"

#include <unistd.h>

#include <atomic>
#include <fstream>
#include <sstream>

namespace lodestone::test {

std::filesystem::path testDataDir() { return LODESTONE_TEST_DATA_DIR; }
std::filesystem::path sharedDataDir() { return LODESTONE_SHARED_DATA_DIR; }
std::filesystem::path mrptDatasetsDir() { return LODESTONE_MRPT_DATASETS_DIR; }
std::filesystem::path sourceDir() { return LODESTONE_SOURCE_DIR; }
std::filesystem::path binaryDir() { return LODESTONE_BINARY_DIR; }

TempDir::TempDir(const std::string& tag) {
    static std::atomic<int> counter{0};
    path_ = std::filesystem::temp_directory_path() /
            (tag + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
}

std::size_t residentSetBytes() {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line)) {
        if (line.rfind("VmRSS:", 0) == 0) {
            std::istringstream in(line.substr(6));
            std::size_t kb = 0;
            in >> kb;
            return kb * 1024;
        }
    }
    return 0;
}

}  // namespace lodestone::test

namespace lodestone::test {

std::string readTextFile(const std::string& path) {
    std::ifstream in(path);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace lodestone::test
