#pragma once

#include <filesystem>
#include <string>

namespace lodestone::test {

std::filesystem::path testDataDir();      ///< tests/data (small fixtures we wrote)
std::filesystem::path sharedDataDir();    ///< ../shared/data (real data, may be absent)
std::filesystem::path mrptDatasetsDir();  ///< /usr/share/mrpt/datasets
std::filesystem::path sourceDir();        ///< the project's source tree
std::filesystem::path binaryDir();        ///< the build tree

/** A fresh, empty directory under the system temp dir, removed when the object dies. */
class TempDir {
  public:
    explicit TempDir(const std::string& tag = "lodestone");
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::filesystem::path& path() const { return path_; }
    std::string file(const std::string& name) const { return (path_ / name).string(); }

  private:
    std::filesystem::path path_;
};

/** The whole file as text; empty if it cannot be read. */
std::string readTextFile(const std::string& path);

/** Resident set size of this process [bytes], from /proc/self/status. */
std::size_t residentSetBytes();

}  // namespace lodestone::test
