// The bad-input matrix, as a user meets it through the apps: every case ends with exit
// 1 (or 2 for usage) and a short message naming the file, key or line - no MRPT call stack,
// no crash - and a rawlog-reading app says so for a missing file, an empty one, a directory, a
// truncated rawlog and a zero-length gzip alike.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "StockTools.h"
#include "TestPaths.h"

namespace {
namespace fs = std::filesystem;
using lodestone::test::runCommand;
const std::string kSlam = LODESTONE_SLAM_BINARY;
const std::string kInspect = LODESTONE_INSPECT_BINARY;
const std::string kEval = LODESTONE_EVAL_BINARY;
const std::string kImport = LODESTONE_IMPORT_BINARY;
const std::string kConfigDir = LODESTONE_CONFIG_INI_DIR;
const std::string kOfficeRawlog = LODESTONE_OFFICE_RAWLOG;

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/** Exit `code`, the output names `what`, and nothing of MRPT's exception dump or a crash. */
void expectNamedError(const lodestone::test::CommandResult& r, int code, const std::string& what,
                      const std::string& context) {
    EXPECT_EQ(r.exitCode, code) << context << "\n" << r.output;
    EXPECT_NE(r.output.find(what), std::string::npos) << context << "\n" << r.output;
    EXPECT_EQ(r.output.find("==== MRPT exception"), std::string::npos) << context << "\n" << r.output;
    EXPECT_EQ(r.output.find("Segmentation"), std::string::npos) << context;
    EXPECT_EQ(r.output.find("terminate called"), std::string::npos) << context;
}
}  // namespace

TEST(BadInputMatrix, RawlogsThatAreNoRawlogsAreNamedByEveryReader) {
    lodestone::test::TempDir dir;
    const std::string bytes = readBytes(kOfficeRawlog);
    ASSERT_GT(bytes.size(), 1000u);
    struct Case {
        std::string name, path;
    };
    std::vector<Case> cases{{"missing", dir.file("absent.rawlog")},
                            {"empty", dir.file("empty.rawlog")},
                            {"a directory", dir.file("folder.rawlog")},
                            {"zero-length gzip", dir.file("empty.rawlog.gz")},
                            {"truncated gzip", dir.file("cut.rawlog.gz")}};
    std::ofstream(dir.file("empty.rawlog")).flush();
    fs::create_directory(dir.file("folder.rawlog"));
    std::ofstream(dir.file("empty.rawlog.gz")).flush();
    std::ofstream(dir.file("cut.rawlog.gz"), std::ios::binary) << bytes.substr(0, bytes.size() / 3);
    for (const auto& c : cases) {
        expectNamedError(runCommand(kInspect + " summary " + c.path), 1, c.path, "inspect: " + c.name);
        const auto slam = runCommand(kSlam + " --rawlog " + c.path + " --config " + kConfigDir +
                                     "/slam/slam.ini --quiet --out " + dir.file("out_" + std::to_string(&c - &cases[0])));
        expectNamedError(slam, 1, c.path, "slam: " + c.name);
    }
}

TEST(BadInputMatrix, ConfigurationValuesAndOutputsAreNamed) {
    lodestone::test::TempDir dir;
    const auto slamWith = [&](const std::string& ini, const std::string& out) {
        std::ofstream(dir.file("bad.ini")) << ini;
        return runCommand(kSlam + " --rawlog " + kOfficeRawlog + " --config " + dir.file("bad.ini") +
                          " --quiet --out " + out);
    };
    const std::string out = dir.file("out");
    expectNamedError(slamWith("[CeresGSO]\nrobust_scale = nan\n", out), 1, "robust_scale", "NaN value");
    expectNamedError(slamWith("[CeresGSO]\nmax_iterations = -1\n", out), 1, "max_iterations",
                     "negative value");
    // An existing file as --out, and a folder that cannot be made.
    std::ofstream(dir.file("a_file")) << "x";
    const std::string slamIni = readBytes(kConfigDir + "/slam/slam.ini");
    expectNamedError(slamWith(slamIni, dir.file("a_file")), 1, dir.file("a_file"), "file as --out");
    EXPECT_EQ(readBytes(dir.file("a_file")), "x");
    expectNamedError(slamWith(slamIni, "/proc/lodestone_cannot_be_here"), 1,
                     "/proc/lodestone_cannot_be_here", "unwritable --out");
}

TEST(BadInputMatrix, TrajectoriesAndCsvFilesAreNamedByLine) {
    lodestone::test::TempDir dir;
    const std::string good = dir.file("good.tum");
    std::ofstream(good) << "1 0 0 0 0 0 0 1\n2 1 0 0 0 0 0 1\n3 2 0 0 0 0 0 1\n";
    const struct {
        const char* name;
        const char* text;
    } tum[] = {{"time going back", "1 0 0 0 0 0 0 1\n0.5 1 0 0 0 0 0 1\n"},
               {"zero quaternion", "1 0 0 0 0 0 0 1\n2 1 0 0 0 0 0 0\n"},
               {"1e308", "1 0 0 0 0 0 0 1\n2 1e308 0 0 0 0 0 1\n"}};
    for (const auto& t : tum) {
        std::ofstream(dir.file("bad.tum")) << t.text;
        expectNamedError(runCommand(kEval + " " + dir.file("bad.tum") + " " + good), 1,
                         dir.file("bad.tum") + ": line 2", t.name);
    }
    const std::string walk = dir.file("walk.csv");
    std::ofstream(walk) << "t,tm,px,py,pz,q0,q1,q2,q3,mx,my,mz\n0,0,0,0,0,1,0,0,0,1,2,3\n"
                           "0.1,0,nan,0,0,1,0,0,0,1,2,3\n";
    expectNamedError(runCommand(kImport + " kok " + walk + " " + dir.file("w.rawlog")), 1,
                     "walk.csv: line 3", "CSV with NaN");
    std::ofstream(walk) << "t,tm,px,py,pz,q0,q1,q2,q3,mx,my,mz\n0,0,0,0,0,1,0,0,0,1,2\n";
    expectNamedError(runCommand(kImport + " kok " + walk + " " + dir.file("w.rawlog")), 1,
                     "walk.csv: line 2", "CSV with a missing column");
    EXPECT_FALSE(fs::exists(dir.file("w.rawlog")));
}
