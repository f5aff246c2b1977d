#include <gtest/gtest.h>
#include <InspectApp.h>
#include <lodestone/obs/registerAllClasses.h>

#include <filesystem>
#include <sstream>

#include "RawlogTestHelpers.h"
#include "SampleObservations.h"
#include "TestPaths.h"

using namespace lodestone;
using inspect::kExitBadInput;
using inspect::kExitOk;
using inspect::kExitUsage;

namespace {
struct Run {
    int code;
    std::string out, err;
};

Run inspectCmd(std::vector<std::string> args) {
    args.insert(args.begin(), "lodestone-inspect");
    std::vector<const char*> argv;
    for (const auto& a : args) argv.push_back(a.c_str());
    std::ostringstream out, err;
    const int code = inspect::runInspectApp(static_cast<int>(argv.size()), argv.data(), out, err);
    return {code, out.str(), err.str()};
}

std::size_t lineCount(const std::string& s) { return std::count(s.begin(), s.end(), '\n'); }
}  // namespace

class InspectApp : public ::testing::Test {
  protected:
    void SetUp() override {
        registerAllClasses();
        path_ = dir_.file("drive.rawlog");
        drive_ = test::makeSampleDrive({2.0});
        test::writeRawlog(path_, drive_);
    }
    test::TempDir dir_;
    std::string path_;
    std::vector<mrpt::obs::CObservation::Ptr> drive_;
};

TEST_F(InspectApp, UsageErrorsExitWith2) {
    EXPECT_EQ(inspectCmd({}).code, kExitUsage);
    const auto unknown = inspectCmd({"summarize", path_});
    EXPECT_EQ(unknown.code, kExitUsage);
    EXPECT_NE(unknown.err.find("unknown command 'summarize'"), std::string::npos);
    EXPECT_EQ(inspectCmd({"summary"}).code, kExitUsage);
    EXPECT_EQ(inspectCmd({"list", path_, "--from", "abc"}).code, kExitUsage);
    EXPECT_EQ(inspectCmd({"list", path_, "--bogus"}).code, kExitUsage);
    const auto badUnit = inspectCmd({"to-imu", path_, dir_.file("x.rawlog"), "--unit", "gaus"});
    EXPECT_EQ(badUnit.code, kExitUsage);
    EXPECT_NE(badUnit.err.find("'gaus'"), std::string::npos) << badUnit.err;
}

TEST_F(InspectApp, HelpExitsWith0) {
    EXPECT_EQ(inspectCmd({"--help"}).code, kExitOk);
    EXPECT_EQ(inspectCmd({"list", "--help"}).code, kExitOk);
}

TEST_F(InspectApp, MissingFileIsBadInputNamingIt) {
    const auto r = inspectCmd({"summary", dir_.file("absent.rawlog")});
    EXPECT_EQ(r.code, kExitBadInput);
    EXPECT_NE(r.err.find("absent.rawlog"), std::string::npos) << r.err;
}

TEST_F(InspectApp, ListOneLinePerEntryWithRangeAndSensorFilter) {
    const auto all = inspectCmd({"list", path_});
    ASSERT_EQ(all.code, kExitOk) << all.err;
    EXPECT_EQ(lineCount(all.out), drive_.size());

    const auto range = inspectCmd({"list", path_, "--from", "10", "--to", "19"});
    EXPECT_EQ(lineCount(range.out), 10u);
    EXPECT_EQ(range.out.rfind("10  ", 0), 0u) << range.out;

    const auto mags = inspectCmd({"list", path_, "--sensor", "MAG_LEFT"});
    EXPECT_EQ(lineCount(mags.out), 201u);  // 2 s at 100 Hz, both ends
    EXPECT_NE(mags.out.find("uT |B|="), std::string::npos);
    EXPECT_EQ(mags.out.find("WHEELS"), std::string::npos);
}

TEST_F(InspectApp, ShowDescribesOneEntry) {
    const auto r = inspectCmd({"show", path_, "1"});
    ASSERT_EQ(r.code, kExitOk) << r.err;
    EXPECT_NE(r.out.find("CObservationMagnetometer"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("Field in the sensor frame [uT]"), std::string::npos) << r.out;

    const auto past = inspectCmd({"show", path_, "999999"});
    EXPECT_EQ(past.code, kExitBadInput);
    EXPECT_NE(past.err.find("has " + std::to_string(drive_.size()) + " entries"), std::string::npos)
        << past.err;
}

TEST_F(InspectApp, CorruptRawlogListsWhatPrecedesTheFaultThenFails) {
    const auto bytes = test::readBytes(path_);
    const auto cut = dir_.file("cut.rawlog");
    test::writeBytes(cut, bytes.substr(0, bytes.size() / 2));
    const auto r = inspectCmd({"list", cut});
    EXPECT_EQ(r.code, kExitBadInput);
    EXPECT_GT(lineCount(r.out), 10u);
    const std::string expected = "entry " + std::to_string(lineCount(r.out)) + " at byte offset";
    EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(cut), std::string::npos) << r.err;

    const auto s = inspectCmd({"summary", cut});
    EXPECT_EQ(s.code, kExitBadInput);
    EXPECT_NE(s.out.find("READ ERROR"), std::string::npos);
}

TEST_F(InspectApp, AnOutputThatIsTheInputIsRefusedAndTheInputKept) {
    const std::string before = test::readBytes(path_);
    const auto link = dir_.file("same.rawlog");
    std::filesystem::create_symlink(path_, link);
    for (const auto& out : {path_, link}) {
        const auto r = inspectCmd({"to-imu", path_, out});
        EXPECT_EQ(r.code, kExitBadInput) << out;
        EXPECT_NE(r.err.find("refusing to overwrite"), std::string::npos) << r.err;
        EXPECT_EQ(test::readBytes(path_), before) << "the input was touched through " << out;
    }
}
