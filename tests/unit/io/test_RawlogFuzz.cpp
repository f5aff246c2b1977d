// Random damage to a rawlog never crashes or hangs the reader: every mutated file either reads
// to its end or stops with a RawlogReadError after delivering the entries before the fault.
#include <gtest/gtest.h>
#include <lodestone/obs/registerAllClasses.h>

#include <random>

#include "RawlogTestHelpers.h"
#include "SampleObservations.h"
#include "TestPaths.h"

using namespace lodestone;

TEST(RawlogFuzz, RandomByteDamageNeverCrashes) {
    registerAllClasses();
    test::TempDir dir;
    const auto clean = dir.file("clean.rawlog");
    test::writeRawlog(clean, test::makeSampleDrive({0.3}));
    const auto original = test::readBytes(clean);
    std::size_t cleanCount = 0;
    {
        io::RawlogSource source(clean);
        cleanCount = test::drain(source).observations.size();
    }

    std::mt19937 rng(20261121);
    const auto path = dir.file("damaged.rawlog");
    std::size_t withError = 0;
    const int kMutations = 200;
    for (int m = 0; m < kMutations; ++m) {
        std::string bytes = original;
        std::uniform_int_distribution<std::size_t> where(0, bytes.size() - 1);
        const int flips = 1 + static_cast<int>(rng() % 8);
        for (int f = 0; f < flips; ++f) bytes[where(rng)] = static_cast<char>(rng() & 0xFF);
        if (rng() % 4 == 0) bytes.resize(where(rng));  // and sometimes truncate
        test::writeBytes(path, bytes);

        io::RawlogSource source(path, {"", 1, "ODOMETRY"});
        const auto got = test::drain(source);
        if (!got.error.empty()) {
            ++withError;
            EXPECT_NE(got.error.find(path), std::string::npos) << got.error;
            EXPECT_LE(got.errorEntry, cleanCount);
        }
    }
    // Most damage is detected; some lands in payload bytes (a changed number) and reads fine.
    EXPECT_GT(withError, static_cast<std::size_t>(kMutations / 4));
    RecordProperty("mutations_with_error", std::to_string(withError));
}
