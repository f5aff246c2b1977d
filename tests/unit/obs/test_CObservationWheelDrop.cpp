#include <gtest/gtest.h>
#include <lodestone/obs/CObservationWheelDrop.h>
#include <lodestone/obs/registerAllClasses.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CFileOutputStream.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/serialization/CArchive.h>

#include <sstream>

#include "TestPaths.h"

using lodestone::obs::CObservationWheelDrop;

namespace {
// The object in tests/data/CObservationWheelDrop_v0.bin: never change these values.
CObservationWheelDrop goldenV0Object() {
    CObservationWheelDrop w;
    w.timestamp = mrpt::Clock::fromDouble(1700000123.5);
    w.sensorLabel = "KOBUKI_WHEEL_DROP";
    w.leftDropped = true;
    w.rightDropped = false;
    return w;
}
const char* kGoldenV0 = "CObservationWheelDrop_v0.bin";
}  // namespace

TEST(WheelDrop, RoundTripAndGoldenV0) {
    lodestone::registerAllClasses();
    for (int bits = 0; bits < 4; ++bits) {
        CObservationWheelDrop w = goldenV0Object();
        w.leftDropped = bits & 1;
        w.rightDropped = bits & 2;
        mrpt::io::CMemoryStream buffer;
        auto archive = mrpt::serialization::archiveFrom(buffer);
        archive << w;
        buffer.Seek(0);
        auto back = std::dynamic_pointer_cast<CObservationWheelDrop>(archive.ReadObject());
        ASSERT_TRUE(back);
        EXPECT_EQ(back->leftDropped, w.leftDropped);
        EXPECT_EQ(back->rightDropped, w.rightDropped);
        EXPECT_EQ(back->lifted(), bits != 0);
        EXPECT_EQ(back->timestamp, w.timestamp);
    }
    const auto path = lodestone::test::testDataDir() / kGoldenV0;
    ASSERT_TRUE(std::filesystem::exists(path)) << path;
    mrpt::io::CFileGZInputStream file(path.string());
    auto golden = std::dynamic_pointer_cast<CObservationWheelDrop>(
        mrpt::serialization::archiveFrom(file).ReadObject());
    ASSERT_TRUE(golden);
    EXPECT_EQ(golden->sensorLabel, "KOBUKI_WHEEL_DROP");
    EXPECT_EQ(golden->timestamp, goldenV0Object().timestamp);
    EXPECT_TRUE(golden->leftDropped);
    EXPECT_FALSE(golden->rightDropped);
}

// Run by hand once per new serialization version (see test_CObservationMagnetometer.cpp).
TEST(WheelDrop, DISABLED_WriteGoldenV0) {
    const auto path = lodestone::test::testDataDir() / kGoldenV0;
    ASSERT_FALSE(std::filesystem::exists(path)) << "refusing to overwrite " << path;
    mrpt::io::CFileOutputStream file(path.string());
    mrpt::serialization::archiveFrom(file) << goldenV0Object();
}

TEST(WheelDrop, ABoolFieldHoldingAnotherByteIsARefusedRead) {
    lodestone::registerAllClasses();
    // The payload ends with left_dropped, right_dropped, then MRPT's end-of-object marker.
    for (const auto& [fromEnd, field] : {std::pair<std::size_t, const char*>{3, "left_dropped"},
                                         {2, "right_dropped"}}) {
        mrpt::io::CMemoryStream buffer;
        auto out = mrpt::serialization::archiveFrom(buffer);
        out << goldenV0Object();
        auto* bytes = static_cast<uint8_t*>(buffer.getRawBufferData());
        bytes[buffer.getTotalBytesCount() - fromEnd] = 8;
        buffer.Seek(0);
        try {
            mrpt::serialization::archiveFrom(buffer).ReadObject();
            ADD_FAILURE() << field << ": byte 8 read as a bool";
        } catch (const std::exception& e) {
            EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
        }
    }
}

TEST(WheelDrop, DescriptionSaysWhichWheelAndWhatItMeans) {
    CObservationWheelDrop d;
    d.rightDropped = true;
    std::ostringstream text;
    d.getDescriptionAsText(text);
    const std::string t = text.str();
    EXPECT_NE(t.find("Left wheel dropped: no"), std::string::npos) << t;
    EXPECT_NE(t.find("Right wheel dropped: yes"), std::string::npos) << t;
    EXPECT_NE(t.find("Robot state: lifted"), std::string::npos) << t;
}
