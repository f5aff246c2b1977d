#include <gtest/gtest.h>
#include <lodestone/io/RawlogReader.h>
#include <lodestone/obs/registerAllClasses.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>

#include <cstring>

#include "RawlogTestHelpers.h"
#include "SampleObservations.h"
#include "TestPaths.h"

using namespace lodestone;

TEST(RawlogSource, SlightlyOutOfOrderEntriesAreReleasedInTimeOrder) {
    registerAllClasses();
    test::TempDir dir;
    const auto path = dir.file("jitter.rawlog");
    std::vector<mrpt::obs::CObservation::Ptr> obs;
    // Two sensors written in bursts: B's samples lag A's by up to 3 entries.
    for (int i = 0; i < 40; ++i) obs.push_back(test::makeMagnetometer(10.0 + i * 0.01, "A", 0));
    for (int i = 0; i < 40; i += 4) std::swap(obs[i], obs[i + 3]);
    test::writeRawlog(path, obs);

    io::RawlogSource source(path, {"", 8, "ODOMETRY"});
    const auto got = test::drain(source);
    ASSERT_EQ(got.observations.size(), obs.size());
    for (std::size_t i = 1; i < got.observations.size(); ++i) {
        EXPECT_LE(got.observations[i - 1]->timestamp, got.observations[i]->timestamp) << i;
    }
    EXPECT_EQ(source.outOfOrder(), 0u);

    io::RawlogSource noWindow(path, {"", 1, "ODOMETRY"});
    test::drain(noWindow);
    EXPECT_GT(noWindow.outOfOrder(), 0u);  // the same file, unsorted, is noticed and counted
}

TEST(RawlogSource, ActionsAndSensoryFramesFormatBecomesObservations) {
    const auto path =
        test::mrptDatasetsDir() / "2006-01ENE-21-SENA_Telecom Faculty_one_loop_only.rawlog";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "MRPT dataset absent: " << path;
    registerAllClasses();

    // Reference: the raw entries and their odometry increments.
    io::RawlogReader reader(path.string());
    std::size_t actionEntries = 0, frames = 0;
    while (auto e = reader.next()) {
        const std::string cls = e->object->GetRuntimeClass()->className;
        actionEntries += cls == "mrpt::obs::CActionCollection";
        frames += cls == "mrpt::obs::CSensoryFrame";
    }
    ASSERT_GT(actionEntries, 100u);

    io::RawlogSource source(path.string());
    const auto got = test::drain(source);
    EXPECT_TRUE(got.error.empty()) << got.error;
    EXPECT_EQ(source.format(), io::RawlogFormat::ActionsSensoryFrames);
    std::size_t odometry = 0;
    mrpt::poses::CPose2D last;
    for (const auto& o : got.observations) {
        if (auto odo = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(o)) {
            ++odometry;
            last = odo->odometry;
        }
    }
    EXPECT_EQ(odometry, actionEntries);  // one odometry action per entry in this dataset
    EXPECT_GT(got.observations.size(), odometry);
    EXPECT_GT(last.norm(), 1.0);  // the accumulated pose moved: increments were composed
}

TEST(RawlogSource, UnstampedActionsTakeTheNextFramesTimeAndAnUnsetEncoderFlagMeansNoTicks) {
    // As in MRPT's localization_demo.rawlog: actions without a timestamp, and an encoder flag
    // an old format version never stored (MRPT leaves the byte as it finds it: 8 there).
    registerAllClasses();
    test::TempDir dir;
    const auto path = dir.file("stock.rawlog");
    test::writeActionsAndFrames(
        path, 3,
        [](auto& move, int) {
            move.timestamp = INVALID_TIMESTAMP;
            const std::uint8_t eight = 8;
            std::memcpy(&move.hasEncodersInfo, &eight, 1);
            move.encoderLeftTicks = 123456;
        },
        [](int k) { return test::makeMagnetometer(10.0 + k, "MAG", k); });
    io::RawlogSource source(path);
    const auto got = test::drain(source);
    ASSERT_TRUE(got.error.empty()) << got.error;
    std::vector<double> odometryTimes;
    for (const auto& o : got.observations) {
        if (auto odo = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(o)) {
            odometryTimes.push_back(mrpt::Clock::toDouble(odo->timestamp));
            EXPECT_FALSE(odo->hasEncodersInfo) << "garbage ticks would be wheel motion";
        }
    }
    EXPECT_EQ(odometryTimes, (std::vector<double>{10.0, 11.0, 12.0}));
    EXPECT_EQ(source.unknownEncoderFlags(), 3u);
}

TEST(RawlogSource, DelayLoadedImagesAreFoundInTheImagesFolderBesideTheRawlog) {
    registerAllClasses();
    test::TempDir dir;
    const auto path = dir.file("ext.rawlog");
    const auto imagesDir = dir.path() / "ext_Images";  // MRPT's naming convention
    std::filesystem::create_directories(imagesDir);
    auto scan = test::makeRangeScan(5.0, 40, 30, 1.0);
    const auto original = scan->intensityImage.makeDeepCopy();
    scan->intensityImage.saveToFile((imagesDir / "rgb_0.png").string());
    scan->intensityImage.setExternalStorage("rgb_0.png");
    test::writeRawlog(path, {scan});

    io::RawlogSource source(path);
    EXPECT_EQ(std::filesystem::path(source.imagesDir()), imagesDir);
    auto read = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(source.next());
    ASSERT_TRUE(read);
    ASSERT_TRUE(read->intensityImage.isExternallyStored());
    read->load();
    ASSERT_EQ(read->intensityImage.getWidth(), 40u);
    EXPECT_EQ(*read->intensityImage.ptr<uint8_t>(7, 9), *original.ptr<uint8_t>(7, 9));
    EXPECT_EQ(*read->intensityImage.ptr<uint8_t>(20, 3), *original.ptr<uint8_t>(20, 3));
}
