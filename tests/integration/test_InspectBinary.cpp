// The installed-style binary, as a user runs it: exit codes and output on the bundled sample.
#include <gtest/gtest.h>

#include <fstream>

#include "StockTools.h"
#include "TestPaths.h"

namespace {
const std::string kInspect = LODESTONE_INSPECT_BINARY;
const std::string kSample = LODESTONE_SAMPLE_RAWLOG;
}  // namespace

TEST(InspectBinary, SummaryOfTheBundledSample) {
    const auto r = lodestone::test::runCommand(kInspect + " summary " + kSample);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("MAG_LEFT"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("lodestone::obs::CObservationMagnetometer"), std::string::npos);
    EXPECT_NE(r.output.find("mrpt::obs::CObservation3DRangeScan"), std::string::npos);
}

TEST(InspectBinary, ExitCodes) {
    EXPECT_EQ(lodestone::test::runCommand(kInspect).exitCode, 2);
    EXPECT_EQ(lodestone::test::runCommand(kInspect + " summary /nonexistent.rawlog").exitCode, 1);
    EXPECT_EQ(lodestone::test::runCommand(kInspect + " show " + kSample + " --help").exitCode, 0);
}

TEST(InspectBinary, GarbageFileFailsCleanly) {
    lodestone::test::TempDir dir;
    const auto path = dir.file("garbage.rawlog");
    {
        std::ofstream out(path, std::ios::binary);
        for (int i = 0; i < 100000; ++i) out.put(static_cast<char>((i * 7919) & 0xFF));
    }
    const auto r = lodestone::test::runCommand(kInspect + " summary " + path);
    EXPECT_EQ(r.exitCode, 1) << r.output;  // not a crash (which would be 128+signal / -1)
    EXPECT_NE(r.output.find("entry 0 at byte offset 0"), std::string::npos) << r.output;
}
