// The bad-input matrix across every app (the cases the first matrix file does not
// cover): every rawlog-reading app and command against a missing file, an empty file, a
// folder, a truncated rawlog, a rawlog with garbage after it (plain and gzip) and a
// zero-length gzip; INI typos, NaN and negative values in each app that takes an INI; output
// paths that cannot be written. Each: exit 1 (2 for usage), the file / key named on one line,
// no MRPT exception dump, no crash, and no output that looks complete.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "StockTools.h"
#include "TestPaths.h"

namespace {
namespace fs = std::filesystem;
using lodestone::test::runCommand;
const std::string kSlam = LODESTONE_SLAM_BINARY;
const std::string kInspect = LODESTONE_INSPECT_BINARY;
const std::string kSim = LODESTONE_SIM_BINARY;
const std::string kMagfit = LODESTONE_MAGFIT_BINARY;
const std::string kImport = LODESTONE_IMPORT_BINARY;
const std::string kConfigDir = LODESTONE_CONFIG_INI_DIR;
const std::string kSample = LODESTONE_SAMPLE_RAWLOG;  // gzip, magnetometers + odometry + RGB-D

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

struct Case {
    std::string name, command;
    int exitCode;
    std::string named;            // text the message must hold (the file, key or line)
    std::string mustNotExist;     // an output that must not be left behind ("" for none)
};

void check(const Case& c) {
    const auto r = runCommand(c.command);
    const std::string context = c.name + "\n$ " + c.command + "\n" + r.output;
    EXPECT_EQ(r.exitCode, c.exitCode) << context;
    EXPECT_NE(r.output.find(c.named), std::string::npos) << context;
    EXPECT_EQ(r.output.find("==== MRPT exception"), std::string::npos) << context;
    EXPECT_EQ(r.output.find("Call stack backtrace"), std::string::npos) << context;
    EXPECT_EQ(r.output.find("terminate called"), std::string::npos) << context;
    EXPECT_EQ(r.output.find("Segmentation"), std::string::npos) << context;
    if (!c.mustNotExist.empty()) {
        EXPECT_FALSE(fs::exists(c.mustNotExist)) << context;
    }
}

/** Every damaged-rawlog shape, made from the bundled sample. */
std::vector<std::pair<std::string, std::string>> damagedRawlogs(const lodestone::test::TempDir& dir) {
    const std::string gz = readBytes(kSample);
    const auto plain = dir.file("plain.rawlog");
    EXPECT_EQ(runCommand("gzip -dc " + kSample + " > " + plain).exitCode, 0);
    const std::string bytes = readBytes(plain);
    writeBytes(dir.file("empty.rawlog"), "");
    fs::create_directory(dir.file("folder.rawlog"));
    writeBytes(dir.file("cut.rawlog"), bytes.substr(0, bytes.size() / 2));
    writeBytes(dir.file("garbage.rawlog"), bytes + "bytes after the last entry");
    writeBytes(dir.file("empty.rawlog.gz"), "");
    writeBytes(dir.file("garbage.rawlog.gz"), gz + "bytes after the gzip data");
    return {{"missing", dir.file("absent.rawlog")},        {"empty", dir.file("empty.rawlog")},
            {"a folder", dir.file("folder.rawlog")},       {"truncated", dir.file("cut.rawlog")},
            {"garbage appended", dir.file("garbage.rawlog")}, {"zero-length gzip", dir.file("empty.rawlog.gz")},
            {"garbage after gzip", dir.file("garbage.rawlog.gz")}};
}
}  // namespace

TEST(BadInputEveryApp, EveryRawlogReaderNamesEveryDamagedRawlog) {
    lodestone::test::TempDir dir;
    int k = 0;
    for (const auto& [shape, path] : damagedRawlogs(dir)) {
        const std::string n = std::to_string(k++);
        const std::vector<Case> cases{
            {"inspect summary: " + shape, kInspect + " summary " + path, 1, path, ""},
            {"inspect list: " + shape, kInspect + " list " + path, 1, path, ""},
            {"inspect export: " + shape,
             kInspect + " export " + path + " --sensor MAG_LEFT --out " + dir.file("export" + n), 1, path,
             dir.file("export" + n) + "/MAG_LEFT.csv"},  // only MAG_LEFT.csv.partial
            {"inspect to-imu: " + shape, kInspect + " to-imu " + path + " " + dir.file("imu" + n + ".rawlog"), 1,
             path, dir.file("imu" + n + ".rawlog")},
            {"magfit: " + shape, kMagfit + " " + path, 1, path, ""},
            {"slam: " + shape,
             kSlam + " --rawlog " + path + " --config " + kConfigDir + "/slam/slam.ini --quiet --out " +
                 dir.file("slam" + n),
             1, path, ""}};
        for (const auto& c : cases) check(c);
        // A slam run that stopped on damaged data writes what it processed, and its report
        // says it stopped: nothing there reads as a complete run.
        const auto report = dir.file("slam" + n) + "/report.json";
        if (fs::exists(report)) {
            EXPECT_NE(readBytes(report).find("\"error\""), std::string::npos) << shape;
        }
    }
}

TEST(BadInputEveryApp, EveryIniIsCheckedBeforeAnyWork) {
    lodestone::test::TempDir dir;
    const std::string office = readBytes(kConfigDir + "/scenarios/office.ini");
    const auto scenarioWith = [&](const std::string& name, const std::string& speedLine) {
        const auto path = dir.file(name);
        writeBytes(path, std::regex_replace(office, std::regex("\nspeed *=[^\n]*"), "\n" + speedLine));
        return path;
    };
    const std::string magneticIni = readBytes(kConfigDir + "/slam/magnetic_only.ini");
    const auto magfitWith = [&](const std::string& name, const std::string& line) {
        const auto path = dir.file(name);
        writeBytes(path, std::regex_replace(magneticIni, std::regex("\\[MagneticGpERD\\]"),
                                            "[MagneticGpERD]\n" + line));
        return path;
    };
    const auto nanLengthScale = dir.file("m2.ini");
    writeBytes(nanLengthScale,
               std::regex_replace(magneticIni, std::regex("\ngp_length_scale *=[^\n]*"), "\ngp_length_scale = nan"));
    const auto slamIni = dir.file("slam_typo.ini");
    writeBytes(slamIni, readBytes(kConfigDir + "/slam/slam.ini") + "\n[CeresGSO]\nmax_iteratons = 10\n");
    const std::vector<Case> cases{
        {"sim: a typo", kSim + " -c " + scenarioWith("typo.ini", "sped = 0.4") + " -o " + dir.file("a.rawlog"), 1,
         "'sped'", dir.file("a.rawlog")},
        {"sim: NaN", kSim + " -c " + scenarioWith("nan.ini", "speed = nan") + " -o " + dir.file("b.rawlog"), 1,
         "'speed'", dir.file("b.rawlog")},
        {"sim: negative", kSim + " -c " + scenarioWith("neg.ini", "speed = -0.4") + " -o " + dir.file("c.rawlog"),
         1, "'speed'", dir.file("c.rawlog")},
        {"sim: missing INI", kSim + " -c " + dir.file("absent.ini") + " -o " + dir.file("d.rawlog"), 1,
         dir.file("absent.ini"), dir.file("d.rawlog")},
        {"magfit: a typo", kMagfit + " " + kSample + " -c " + magfitWith("m1.ini", "gp_sigmaf = 3"), 1,
         "gp_sigmaf", ""},
        {"magfit: NaN", kMagfit + " " + kSample + " -c " + nanLengthScale, 1, "gp_length_scale", ""},
        {"slam: a typo", kSlam + " --rawlog " + kSample + " --config " + slamIni + " --quiet --out " +
                             dir.file("s"), 1, "max_iteratons", dir.file("s") + "/report.json"}};
    for (const auto& c : cases) check(c);
}

TEST(BadInputEveryApp, OutputsThatCannotBeWrittenAreNamedFirst) {
    lodestone::test::TempDir dir;
    fs::create_directory(dir.file("a_folder.rawlog"));
    const std::string walk = dir.file("walk.csv");
    writeBytes(walk, "t,tm,px,py,pz,q0,q1,q2,q3,mx,my,mz\n0,0,0,0,0,1,0,0,0,10,20,30\n1,1,1,0,0,1,0,0,0,10,20,30\n");
    const std::string unwritable = "/proc/lodestone_cannot_be_here/out.rawlog";
    const std::vector<Case> cases{
        {"sim: an unwritable folder", kSim + " -c " + kConfigDir + "/scenarios/office.ini -o " + unwritable, 1,
         unwritable, ""},
        {"sim: --out is a folder", kSim + " -c " + kConfigDir + "/scenarios/office.ini -o " + dir.file("a_folder.rawlog"), 1,
         dir.file("a_folder.rawlog"), dir.file("a_folder_Images")},
        {"inspect to-imu: an unwritable folder", kInspect + " to-imu " + kSample + " " + unwritable, 1,
         "/proc/lodestone_cannot_be_here", ""},
        {"import kok: an unwritable folder", kImport + " kok " + walk + " " + unwritable, 1,
         "/proc/lodestone_cannot_be_here", ""},
        {"import kok: --out is a folder", kImport + " kok " + walk + " " + dir.file("a_folder.rawlog"), 1,
         dir.file("a_folder.rawlog"), ""}};
    for (const auto& c : cases) check(c);
}
