#include <gtest/gtest.h>
#include <lodestone/io/RawlogPaths.h>
#include <lodestone/io/RawlogReader.h>
#include <lodestone/obs/registerAllClasses.h>

#include <filesystem>

#include "RawlogTestHelpers.h"
#include "SampleObservations.h"
#include "TestPaths.h"

using namespace lodestone;

namespace {
std::vector<mrpt::obs::CObservation::Ptr> everyKind() {
    return {test::makeRangeScan(100.0, 64, 48, 1.0),
            test::makeOdometry(100.01, 2.0),
            test::makeImu(100.02, "IMU", 3.0),
            test::makeMagnetometer(100.03, "MAG_LEFT", 4.0),
            test::makeMagnetometer(100.04, "MAG_RIGHT", 5.0),
            test::makeRangeScan(100.05, 64, 48, 2.0)};
}
}  // namespace

class RawlogRoundTrip : public ::testing::TestWithParam<int> {
  protected:
    void SetUp() override { registerAllClasses(); }
};

TEST_P(RawlogRoundTrip, EveryObservationKindReadsBackEqual) {
    test::TempDir dir;
    const auto path = dir.file(GetParam() > 0 ? "all.rawlog.gz" : "all.rawlog");
    const auto written = everyKind();
    test::writeRawlog(path, written, GetParam());

    io::RawlogReader reader(path);
    EXPECT_EQ(reader.isCompressed(), GetParam() > 0);
    std::size_t n = 0;
    std::uint64_t lastOffset = 0;
    while (auto entry = reader.next()) {
        ASSERT_LT(n, written.size());
        EXPECT_EQ(entry->index, n);
        if (n > 0) {
            EXPECT_GT(entry->byteOffset, lastOffset);
        }
        lastOffset = entry->byteOffset;
        EXPECT_TRUE(test::serializeEqual(*entry->object, *written[n]))
            << "entry " << n << " (" << written[n]->GetRuntimeClass()->className << ") differs";
        ++n;
    }
    EXPECT_EQ(n, written.size());
}

TEST_P(RawlogRoundTrip, SourceYieldsTheSameObservationsInOrder) {
    test::TempDir dir;
    const auto path = dir.file("all.rawlog");
    const auto written = everyKind();
    test::writeRawlog(path, written, GetParam());
    io::RawlogSource source(path);
    const auto got = test::drain(source);
    EXPECT_TRUE(got.error.empty()) << got.error;
    ASSERT_EQ(got.observations.size(), written.size());
    for (std::size_t i = 0; i < written.size(); ++i) {
        EXPECT_TRUE(test::serializeEqual(*got.observations[i], *written[i])) << i;
    }
    EXPECT_EQ(source.format(), io::RawlogFormat::Observations);
}

INSTANTIATE_TEST_SUITE_P(PlainAndGzip, RawlogRoundTrip, ::testing::Values(0, 6),
                         [](const auto& info) { return info.param ? "gzip" : "plain"; });

TEST(RawlogWriter, EachEntryIsOnDiskBeforeTheNextIsWritten) {
    registerAllClasses();
    for (int level : {0, 1}) {
        test::TempDir dir;
        const auto path = dir.file("live.rawlog");
        io::RawlogWriter writer(path, {level});
        for (int i = 0; i < 5; ++i) {
            writer.write(*test::makeMagnetometer(10.0 + i, "MAG", i));
            // A snapshot of the file now (still the .partial one) is what a crash would leave.
            const auto snapshot = dir.file("snapshot.rawlog");
            test::writeBytes(snapshot, test::readBytes(io::partialPath(path)));
            io::RawlogSource source(snapshot);
            const auto got = test::drain(source);
            EXPECT_EQ(got.observations.size(), static_cast<std::size_t>(i + 1))
                << "gzip level " << level << ", after entry " << i << ": " << got.error;
        }
    }
}

TEST(RawlogWriter, AFailedRunLeavesAPartialFileAndThePreviousOutputUntouched) {
    // Written to OUT.partial, renamed at close: a run that stops with an error never leaves a
    // file that looks complete, nor replaces the previous run's.
    registerAllClasses();
    test::TempDir dir;
    const auto path = dir.file("out.rawlog");
    test::writeBytes(path, "previous run");
    try {
        io::RawlogWriter writer(path);
        writer.write(*test::makeMagnetometer(1.0, "MAG", 1));
        throw std::runtime_error("the run failed");
    } catch (const std::runtime_error&) {
    }
    EXPECT_EQ(test::readBytes(path), "previous run");
    io::RawlogSource partial(io::partialPath(path));
    EXPECT_EQ(test::drain(partial).observations.size(), 1u);  // what was written is kept
    {
        io::RawlogWriter writer(path);
        writer.write(*test::makeMagnetometer(2.0, "MAG", 2));
    }  // the normal end of the scope completes the file
    EXPECT_FALSE(std::filesystem::exists(io::partialPath(path)));
    io::RawlogSource complete(path);
    EXPECT_EQ(test::drain(complete).observations.size(), 1u);
}

TEST(RawlogWriter, UnwritablePathIsAClearError) {
    try {
        io::RawlogWriter writer("/nonexistent-dir/x.rawlog");
        FAIL();
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/x.rawlog"), std::string::npos);
    }
}
