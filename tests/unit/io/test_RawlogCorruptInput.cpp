// Every kind of broken rawlog gives an error naming the file, the failing entry and its byte
// offset, after delivering every entry before the fault; none crashes or hangs.
#include <gtest/gtest.h>
#include <lodestone/io/RawlogReader.h>
#include <lodestone/obs/registerAllClasses.h>

#include <random>

#include "RawlogTestHelpers.h"
#include "SampleObservations.h"
#include "TestPaths.h"

using namespace lodestone;

class RawlogCorruptInput : public ::testing::Test {
  protected:
    void SetUp() override {
        registerAllClasses();
        for (int i = 0; i < 10; ++i) {
            observations_.push_back(test::makeMagnetometer(50.0 + i, "MAG", i));
            observations_.push_back(test::makeOdometry(50.0 + i + 0.5, i));
        }
        clean_ = dir_.file("clean.rawlog");
        test::writeRawlog(clean_, observations_);
        // Offsets where each entry starts, from the reader itself on the clean file.
        io::RawlogReader reader(clean_);
        while (auto e = reader.next()) offsets_.push_back(e->byteOffset);
        file_size_ = test::readBytes(clean_).size();
    }

    /** Checks what a source on `path` yields: `goodEntries` observations, then an error at
     * entry `goodEntries` naming the file, the offset and `reasonPart`. */
    void expectFaultAt(const std::string& path, std::size_t goodEntries,
                       const std::string& reasonPart) {
        io::RawlogSource source(path, {"", 1, "ODOMETRY"});
        const auto got = test::drain(source);
        ASSERT_EQ(got.observations.size(), goodEntries) << got.error;
        for (std::size_t i = 0; i < goodEntries; ++i) {
            EXPECT_TRUE(test::serializeEqual(*got.observations[i], *observations_[i])) << i;
        }
        ASSERT_FALSE(got.error.empty()) << "no error reported for " << path;
        EXPECT_EQ(got.errorEntry, goodEntries);
        EXPECT_EQ(got.errorOffset, offsets_.at(goodEntries));
        EXPECT_NE(got.error.find(path), std::string::npos) << got.error;
        EXPECT_NE(got.error.find("entry " + std::to_string(goodEntries)), std::string::npos)
            << got.error;
        EXPECT_NE(got.error.find("byte offset " + std::to_string(offsets_.at(goodEntries))),
                  std::string::npos)
            << got.error;
        EXPECT_NE(got.error.find(reasonPart), std::string::npos) << got.error;
    }

    test::TempDir dir_;
    std::vector<mrpt::obs::CObservation::Ptr> observations_;
    std::vector<std::uint64_t> offsets_;
    std::string clean_;
    std::size_t file_size_{0};
};

TEST_F(RawlogCorruptInput, CleanFileHasNoError) {
    io::RawlogSource source(clean_);
    const auto got = test::drain(source);
    EXPECT_TRUE(got.error.empty()) << got.error;
    EXPECT_EQ(got.observations.size(), observations_.size());
    EXPECT_EQ(offsets_.size(), observations_.size());
}

TEST_F(RawlogCorruptInput, TruncatedPlainFile) {
    const auto bytes = test::readBytes(clean_);
    const auto path = dir_.file("truncated.rawlog");
    test::writeBytes(path, bytes.substr(0, offsets_[7] + 10));  // cut inside entry 7
    expectFaultAt(path, 7, "truncated");
}

TEST_F(RawlogCorruptInput, TruncatedGzipFile) {
    const auto gz = dir_.file("clean.rawlog.gz");
    test::writeRawlog(gz, observations_, 9);
    const auto bytes = test::readBytes(gz);
    const auto path = dir_.file("truncated.rawlog.gz");
    test::writeBytes(path, bytes.substr(0, bytes.size() / 2));
    io::RawlogSource source(path);
    const auto got = test::drain(source);
    ASSERT_FALSE(got.error.empty());
    EXPECT_GT(got.observations.size(), 0u);
    EXPECT_LT(got.observations.size(), observations_.size());
    EXPECT_EQ(got.errorEntry, got.observations.size());
    EXPECT_EQ(got.errorOffset, offsets_.at(got.errorEntry));
    EXPECT_NE(got.error.find(path), std::string::npos) << got.error;
}

TEST_F(RawlogCorruptInput, GarbageAfterTheGzipDataIsAnError) {
    // zlib's gzread ignores what follows the last gzip member; a rawlog with bytes after its
    // compressed data is damaged (or two files run together), and the reader says so after
    // delivering every entry.
    const auto gz = dir_.file("clean.rawlog.gz");
    test::writeRawlog(gz, observations_, 6);
    const auto path = dir_.file("garbage_after.rawlog.gz");
    test::writeBytes(path, test::readBytes(gz) + "trailing garbage");
    io::RawlogSource source(path);
    const auto got = test::drain(source);
    EXPECT_EQ(got.observations.size(), observations_.size());
    EXPECT_EQ(got.errorEntry, observations_.size());
    EXPECT_NE(got.error.find("garbage after the end of the gzip data"), std::string::npos) << got.error;
    EXPECT_NE(got.error.find(path), std::string::npos) << got.error;
}

TEST_F(RawlogCorruptInput, ConcatenatedGzipMembersReadAsOneRawlog) {
    // gzip allows members back to back (cat a.gz b.gz): both halves are read.
    const auto first = dir_.file("first.rawlog.gz");
    const auto second = dir_.file("second.rawlog.gz");
    const std::size_t half = observations_.size() / 2;
    test::writeRawlog(first, {observations_.begin(), observations_.begin() + half}, 6);
    test::writeRawlog(second, {observations_.begin() + half, observations_.end()}, 6);
    const auto path = dir_.file("both.rawlog.gz");
    test::writeBytes(path, test::readBytes(first) + test::readBytes(second));
    io::RawlogSource source(path);
    const auto got = test::drain(source);
    EXPECT_TRUE(got.error.empty()) << got.error;
    ASSERT_EQ(got.observations.size(), observations_.size());
    for (std::size_t i = 0; i < observations_.size(); ++i) {
        EXPECT_TRUE(test::serializeEqual(*got.observations[i], *observations_[i])) << i;
    }
}

TEST_F(RawlogCorruptInput, GarbageBytesBetweenEntries) {
    auto bytes = test::readBytes(clean_);
    std::mt19937 rng(7);
    std::string garbage(64, '\0');
    for (auto& c : garbage) c = static_cast<char>(rng() & 0xFF);
    bytes.insert(offsets_[4], garbage);
    const auto path = dir_.file("garbage.rawlog");
    test::writeBytes(path, bytes);
    expectFaultAt(path, 4, "");
}

TEST_F(RawlogCorruptInput, GarbageBytesInsideAnEntry) {
    auto bytes = test::readBytes(clean_);
    // Overwrite the middle of entry 5's payload: whatever the reader makes of it, it must stop
    // with an error at entry 5 or later, never crash, never invent entries before it.
    for (std::uint64_t i = offsets_[5] + 50; i < offsets_[6] && i < offsets_[5] + 90; ++i) {
        bytes[i] = static_cast<char>(0xFF);
    }
    const auto path = dir_.file("garbage-inside.rawlog");
    test::writeBytes(path, bytes);
    io::RawlogSource source(path, {"", 1, "ODOMETRY"});
    const auto got = test::drain(source);
    ASSERT_GE(got.observations.size(), 5u);
    for (std::size_t i = 0; i < 5; ++i) {
        EXPECT_TRUE(test::serializeEqual(*got.observations[i], *observations_[i])) << i;
    }
    if (!got.error.empty()) {
        EXPECT_NE(got.error.find(path), std::string::npos);
    }
}

TEST_F(RawlogCorruptInput, UnregisteredClass) {
    auto bytes = test::readBytes(clean_);
    // Rename the class of entry 3 (a magnetometer... or odometry) to one nobody registered.
    const std::string from = "CObservationOdometry", to = "CObservationOdXmetry";
    const auto at = bytes.find(from, offsets_[3]);
    ASSERT_LT(at, offsets_[4]);
    bytes.replace(at, from.size(), to);
    const auto path = dir_.file("unregistered.rawlog");
    test::writeBytes(path, bytes);
    expectFaultAt(path, 3, "CObservationOdXmetry");
}

TEST_F(RawlogCorruptInput, PureGarbageFile) {
    std::mt19937 rng(11);
    std::string garbage(4096, '\0');
    for (auto& c : garbage) c = static_cast<char>(rng() & 0xFF);
    const auto path = dir_.file("noise.rawlog");
    test::writeBytes(path, garbage);
    io::RawlogSource source(path);
    const auto got = test::drain(source);
    EXPECT_TRUE(got.observations.empty());
    EXPECT_EQ(got.errorEntry, 0u);
    EXPECT_EQ(got.errorOffset, 0u);
    EXPECT_NE(got.error.find(path), std::string::npos) << got.error;
}

TEST_F(RawlogCorruptInput, AnEmptyFileOrAnEmptyGzipIsNoRawlog) {
    const auto empty = dir_.file("empty.rawlog");
    test::writeBytes(empty, "");
    const auto emptyGz = dir_.file("empty.rawlog.gz");
    test::writeRawlog(emptyGz, {}, 6);  // a valid gzip stream of nothing
    for (const auto& path : {empty, emptyGz}) {
        io::RawlogSource source(path);
        const auto got = test::drain(source);
        EXPECT_TRUE(got.observations.empty());
        EXPECT_NE(got.error.find(path), std::string::npos) << got.error;
        EXPECT_NE(got.error.find("no entries"), std::string::npos) << got.error;
        EXPECT_EQ(got.errorEntry, 0u);
    }
}

TEST_F(RawlogCorruptInput, MissingFileNamesThePath) {
    try {
        io::RawlogSource source(dir_.file("nope.rawlog"));
        FAIL();
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("nope.rawlog"), std::string::npos) << e.what();
    }
}
