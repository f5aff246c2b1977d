// The reader streams: memory stays flat however long the rawlog is.
#include <gtest/gtest.h>
#include <lodestone/obs/registerAllClasses.h>

#include "RawlogTestHelpers.h"
#include "SampleObservations.h"
#include "TestPaths.h"

using namespace lodestone;

TEST(RawlogStreaming, MemoryStaysFlatOverALargeRawlog) {
#if defined(__SANITIZE_ADDRESS__)
    GTEST_SKIP() << "AddressSanitizer keeps freed memory in quarantine, so RSS says nothing here";
#endif
    registerAllClasses();
    test::TempDir dir;
    const auto path = dir.file("large.rawlog");
    // ~200 k entries, ~60 MB: had the reader kept what it read, RSS would grow by well over
    // 100 MB (a decoded CObservation is far larger than its bytes).
    const std::size_t n = 200000;
    {
        io::RawlogWriter writer(path);
        auto mag = test::makeMagnetometer(0, "MAG", 2.0);
        auto scan = test::makeRangeScan(0, 32, 24, 1.0);
        for (std::size_t i = 0; i < n; ++i) {
            auto& obs = (i % 50 == 0) ? static_cast<mrpt::obs::CObservation&>(*scan)
                                      : static_cast<mrpt::obs::CObservation&>(*mag);
            obs.timestamp = mrpt::Clock::fromDouble(1000.0 + 0.001 * i);
            writer.write(obs);
        }
    }
    const auto fileBytes = std::filesystem::file_size(path);

    io::RawlogSource source(path);
    std::size_t count = 0, rssAfterWarmup = 0;
    while (auto o = source.next()) {
        if (++count == n / 10) rssAfterWarmup = test::residentSetBytes();
    }
    const std::size_t rssAtEnd = test::residentSetBytes();
    EXPECT_EQ(count, n);
    ASSERT_GT(rssAfterWarmup, 0u);
    const double growthMiB =
        (static_cast<double>(rssAtEnd) - static_cast<double>(rssAfterWarmup)) / (1 << 20);
    RecordProperty("file_MiB", std::to_string(fileBytes >> 20));
    RecordProperty("rss_growth_MiB", std::to_string(growthMiB));
    // 90 % of the file read after the warm-up point; allow allocator noise, not accumulation.
    EXPECT_LT(growthMiB, 4.0) << "file " << (fileBytes >> 20) << " MiB";
}
