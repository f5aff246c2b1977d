// A damaged size field in a rawlog entry: MRPT's deserializers allocate what the
// field says before reading, so a label length of 0xF0000000, a 100 000 x 100 000 range image
// or an action count of 0xFFFFFFFF took gigabytes (or crashed). Each must end in a read error
// naming the entry, after the entries before it, in well under a second and 200 MB.
#include <gtest/gtest.h>
#include <lodestone/io/RawlogReader.h>
#include <lodestone/io/RawlogSource.h>
#include <lodestone/obs/registerAllClasses.h>

#include <chrono>
#include <cstring>

#include "RawlogTestHelpers.h"
#include "SampleObservations.h"
#include "TestPaths.h"

using namespace lodestone;

namespace {
/** Replaces the first occurrence of `from` at or after `start` with `to` (same length). */
std::size_t patch(std::string& bytes, const std::string& from, const std::string& to,
                  std::size_t start = 0) {
    const auto at = bytes.find(from, start);
    if (at == std::string::npos) return at;
    bytes.replace(at, to.size(), to);
    return at;
}

std::string le32(std::uint32_t v) {
    std::string s(4, '\0');
    std::memcpy(s.data(), &v, 4);
    return s;
}

struct Outcome {
    test::Drained drained;
    double seconds{0};
    std::size_t residentGrowth{0};
};

Outcome readAll(const std::string& path) {
    const std::size_t before = test::residentSetBytes();
    const auto t0 = std::chrono::steady_clock::now();
    io::RawlogSource source(path);
    Outcome o;
    o.drained = test::drain(source);
    o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const std::size_t after = test::residentSetBytes();
    o.residentGrowth = after > before ? after - before : 0;
    return o;
}

void expectRefusedSize(const Outcome& o, std::size_t goodEntries, const std::string& path) {
    EXPECT_EQ(o.drained.observations.size(), goodEntries) << o.drained.error;
    EXPECT_EQ(o.drained.errorEntry, goodEntries) << o.drained.error;
    EXPECT_NE(o.drained.error.find(path), std::string::npos) << o.drained.error;
    EXPECT_NE(o.drained.error.find("size field"), std::string::npos) << o.drained.error;
    EXPECT_LT(o.seconds, 1.0);
    EXPECT_LT(o.residentGrowth, 200u << 20);
}
}  // namespace

TEST(RawlogSizeFields, AHugeLabelLengthIsRefusedNotAllocated) {
    registerAllClasses();
    test::TempDir dir;
    const auto path = dir.file("label.rawlog");
    test::writeRawlog(path, {test::makeMagnetometer(1.0, "MAGA", 1), test::makeMagnetometer(2.0, "MAGB", 2)});
    std::string bytes = test::readBytes(path);
    ASSERT_NE(patch(bytes, le32(4) + "MAGB", le32(0xF0000000u) + "MAGB"), std::string::npos);
    test::writeBytes(path, bytes);
    expectRefusedSize(readAll(path), 1, path);
}

TEST(RawlogSizeFields, AHugeRangeImageIsRefusedNotAllocated) {
    registerAllClasses();
    test::TempDir dir;
    const auto path = dir.file("range.rawlog");
    test::writeRawlog(path, {test::makeMagnetometer(1.0, "MAG", 1), test::makeRangeScan(2.0, 64, 48, 1.0)});
    std::string bytes = test::readBytes(path);
    // The range image is stored as rows, cols (uint32 each), then the pixels.
    ASSERT_NE(patch(bytes, le32(48) + le32(64), le32(100000) + le32(100000)), std::string::npos);
    test::writeBytes(path, bytes);
    expectRefusedSize(readAll(path), 1, path);
}

TEST(RawlogSizeFields, AHugeImageSizeIsRefusedNotAllocated) {
    // MRPT's CImage keeps its pixels in a cv::Mat, which OpenCV takes from malloc (not through
    // operator new): the reader's cv::Mat allocator charges the budget too. The colour image of
    // an RGB-D frame stored raw: its width and height precede the pixels (as int32, negated:
    // MRPT's mark for an uncompressed image).
    registerAllClasses();
    test::TempDir dir;
    const auto path = dir.file("image.rawlog");
    test::writeRawlog(path, {test::makeMagnetometer(1.0, "MAG", 1), test::makeRangeScan(2.0, 64, 48, 1.0)});
    std::string bytes = test::readBytes(path);
    const auto at = patch(bytes, le32(static_cast<std::uint32_t>(-64)) + le32(static_cast<std::uint32_t>(-48)),
                          le32(static_cast<std::uint32_t>(-(1 << 20))) + le32(static_cast<std::uint32_t>(-(1 << 20))));
    ASSERT_NE(at, std::string::npos);
    test::writeBytes(path, bytes);
    expectRefusedSize(readAll(path), 1, path);
}

TEST(RawlogSizeFields, AnActionCountOfFourBillionIsRefusedNotLooped) {
    registerAllClasses();
    test::TempDir dir;
    const auto path = dir.file("actions.rawlog");
    test::writeActionsAndFrames(
        path, 2, [](auto& move, int k) { move.timestamp = mrpt::Clock::fromDouble(1.0 + k); },
        [](int k) { return test::makeMagnetometer(1.0 + k, "MAG", k); });
    std::string bytes = test::readBytes(path);
    const std::string name = "CActionCollection";
    const auto first = bytes.find(name);
    const auto second = bytes.find(name, first + 1);
    ASSERT_NE(second, std::string::npos);
    // After the class name: its version (one byte), then the number of actions.
    ASSERT_EQ(bytes.substr(second + name.size() + 1, 4), le32(1));
    bytes.replace(second + name.size() + 1, 4, le32(0xFFFFFFFFu));
    test::writeBytes(path, bytes);
    const auto o = readAll(path);
    EXPECT_FALSE(o.drained.error.empty());
    EXPECT_NE(o.drained.error.find(path), std::string::npos) << o.drained.error;
    EXPECT_NE(o.drained.error.find("entry 2"), std::string::npos) << o.drained.error;
    EXPECT_LT(o.seconds, 1.0);
    EXPECT_LT(o.residentGrowth, 200u << 20);
}
