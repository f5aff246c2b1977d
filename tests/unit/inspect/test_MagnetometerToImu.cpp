#include <gtest/gtest.h>
#include <lodestone/inspect/MagnetometerToImu.h>
#include <lodestone/inspect/RawlogSummary.h>
#include <lodestone/obs/registerAllClasses.h>

#include "RawlogTestHelpers.h"
#include "SampleObservations.h"
#include "StockTools.h"
#include "TestPaths.h"

using namespace lodestone;

TEST(MagnetometerToImu, RewrittenRawlogHasNoMagnetometersAndStockMrptReadsIt) {
    registerAllClasses();
    test::TempDir dir;
    const auto in = dir.file("drive.rawlog");
    const auto out = dir.file("drive_imu.rawlog.gz");
    test::writeRawlog(in, test::makeSampleDrive({1.0}));
    const auto r = inspect::magnetometersToImu(in, out, obs::MagneticUnit::gauss());
    EXPECT_EQ(r.converted, 202u);

    const auto before = inspect::summarizeRawlog(in);
    const auto after = inspect::summarizeRawlog(out);
    EXPECT_TRUE(after.compressed);
    EXPECT_EQ(after.entries, before.entries);
    EXPECT_EQ(after.observationClasses.count("lodestone::obs::CObservationMagnetometer"), 0u);
    EXPECT_EQ(after.sensors.at("MAG_LEFT").count, 101u);
    EXPECT_EQ(after.sensors.at("MAG_LEFT").classes.count("mrpt::obs::CObservationIMU"), 1u);

    if (!test::haveRawlogEdit()) GTEST_SKIP() << "rawlog-edit (Debian mrpt-apps) not installed";
    // The stock tool cannot read our original file, but reads the rewritten one in full.
    const auto info = test::rawlogEditInfo(out);
    EXPECT_EQ(info.objects, static_cast<long>(before.entries));
    EXPECT_EQ(info.occurrences.at("MAG_LEFT"), 101);
}
