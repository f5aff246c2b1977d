#include <gtest/gtest.h>
#include <lodestone/obs/CObservationMagnetometer.h>
#include <lodestone/obs/registerAllClasses.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CFileOutputStream.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/rtti/CObject.h>
#include <mrpt/serialization/CArchive.h>

#include <sstream>

#include "SampleObservations.h"
#include "TestPaths.h"

using lodestone::obs::CObservationMagnetometer;

namespace {

// The object stored in tests/data/CObservationMagnetometer_v0.bin. Never change these values:
// the golden file was written from them and must keep loading as the class evolves.
CObservationMagnetometer goldenV0Object() {
    CObservationMagnetometer m;
    m.timestamp = mrpt::Clock::fromDouble(1700000000.25);
    m.sensorLabel = "MAG_LEFT";
    m.sensorPose = mrpt::poses::CPose3D(0.1, -0.2, 0.3, 0.5, 0.0, -0.25);
    m.field = {21.5, -3.25, -44.0};
    m.noiseStd = {0.2, 0.25, 0.5};
    m.temperature = 23.75;
    m.calibrated = true;
    return m;
}

const char* kGoldenV0 = "CObservationMagnetometer_v0.bin";

CObservationMagnetometer::Ptr roundTrip(const CObservationMagnetometer& in) {
    mrpt::io::CMemoryStream buffer;
    auto out = mrpt::serialization::archiveFrom(buffer);
    out << in;
    buffer.Seek(0);
    auto read = mrpt::serialization::archiveFrom(buffer).ReadObject();
    return std::dynamic_pointer_cast<CObservationMagnetometer>(read);
}

void expectSame(const CObservationMagnetometer& a, const CObservationMagnetometer& b) {
    EXPECT_EQ(a.timestamp, b.timestamp);
    EXPECT_EQ(a.sensorLabel, b.sensorLabel);
    EXPECT_EQ(a.sensorPose, b.sensorPose);
    EXPECT_EQ(a.field, b.field);
    EXPECT_EQ(a.noiseStd, b.noiseStd);
    EXPECT_EQ(a.temperature, b.temperature);
    EXPECT_EQ(a.calibrated, b.calibrated);
}

}  // namespace

class MagnetometerTest : public ::testing::Test {
  protected:
    void SetUp() override { lodestone::registerAllClasses(); }
};

TEST_F(MagnetometerTest, RegisteredUnderItsFullName) {
    const auto* cls = mrpt::rtti::findRegisteredClass("lodestone::obs::CObservationMagnetometer");
    ASSERT_NE(cls, nullptr);
    EXPECT_TRUE(cls->derivedFrom(CLASS_ID(mrpt::obs::CObservation)));
}

TEST_F(MagnetometerTest, RoundTripKeepsEveryField) {
    for (double seed : {0.0, 1.0, 7.0}) {  // even seeds carry a temperature, odd ones not
        auto original = lodestone::test::makeMagnetometer(1.7e9 + seed, "MAG", seed);
        auto copy = roundTrip(*original);
        ASSERT_TRUE(copy);
        expectSame(*original, *copy);
    }
}

TEST_F(MagnetometerTest, MissingTemperatureStaysMissing) {
    auto m = goldenV0Object();
    m.temperature.reset();
    auto copy = roundTrip(m);
    ASSERT_TRUE(copy);
    EXPECT_FALSE(copy->temperature.has_value());
}

TEST_F(MagnetometerTest, GoldenV0FileStillLoads) {
    const auto path = lodestone::test::testDataDir() / kGoldenV0;
    ASSERT_TRUE(std::filesystem::exists(path)) << path;
    mrpt::io::CFileGZInputStream file(path.string());
    auto object = mrpt::serialization::archiveFrom(file).ReadObject();
    auto m = std::dynamic_pointer_cast<CObservationMagnetometer>(object);
    ASSERT_TRUE(m) << "golden file holds " << object->GetRuntimeClass()->className;
    expectSame(goldenV0Object(), *m);
}

TEST_F(MagnetometerTest, UnknownFutureVersionIsRejectedNotMisread) {
    mrpt::io::CMemoryStream buffer;
    auto out = mrpt::serialization::archiveFrom(buffer);
    out << goldenV0Object();
    // The byte after the class name is the version: bump it to one this build cannot know.
    auto* bytes = static_cast<uint8_t*>(buffer.getRawBufferData());
    const std::string name = "lodestone::obs::CObservationMagnetometer";
    const std::string all(reinterpret_cast<char*>(bytes), buffer.getTotalBytesCount());
    const auto at = all.find(name);
    ASSERT_NE(at, std::string::npos);
    bytes[at + name.size()] = 200;
    buffer.Seek(0);
    EXPECT_ANY_THROW(mrpt::serialization::archiveFrom(buffer).ReadObject());
}

TEST_F(MagnetometerTest, DescriptionAndTextExport) {
    const auto m = goldenV0Object();
    std::ostringstream text;
    m.getDescriptionAsText(text);
    EXPECT_NE(text.str().find("21.500"), std::string::npos) << text.str();
    EXPECT_NE(text.str().find("23.750"), std::string::npos) << text.str();
    EXPECT_NE(text.str().find("Calibrated: yes"), std::string::npos) << text.str();

    ASSERT_TRUE(m.exportTxtSupported());
    std::istringstream header(m.exportTxtHeader()), row(m.exportTxtDataRow());
    std::vector<std::string> columns, values;
    for (std::string w; header >> w;) columns.push_back(w);
    for (std::string w; row >> w;) values.push_back(w);
    EXPECT_EQ(columns.size(), values.size());
    EXPECT_EQ(values.at(0), "21.5");
    EXPECT_EQ(values.at(6), "23.75");
}

TEST_F(MagnetometerTest, DescriptionGivesUnitsRobotFrameAndNoiseOfTheMagnitude) {
    // A sensor yawed +90 deg on the robot: its x axis is the robot's y axis.
    CObservationMagnetometer m;
    m.sensorPose = mrpt::poses::CPose3D(0, 0, 0, M_PI / 2, 0, 0);
    m.field = {30.0, 0.0, 0.0};
    m.noiseStd = {0.4, 5.0, 5.0};  // only the x noise moves |B| of a field along x
    std::ostringstream text;
    m.getDescriptionAsText(text);
    const std::string t = text.str();
    EXPECT_NE(t.find("microtesla"), std::string::npos) << t;
    EXPECT_NE(t.find("Field in the robot frame [uT]: (0.000, 30.000, 0.000)"), std::string::npos)
        << t;
    EXPECT_NE(t.find("std of |B| about 0.400 uT"), std::string::npos) << t;
    EXPECT_NE(t.find("Calibrated: no (raw reading"), std::string::npos) << t;
    EXPECT_NE(t.find("Temperature [degC]: (not reported)"), std::string::npos) << t;
}

TEST_F(MagnetometerTest, SensorPoseAccessors) {
    CObservationMagnetometer m;
    const mrpt::poses::CPose3D pose(1, 2, 3, 0.1, 0.2, 0.3);
    m.setSensorPose(pose);
    mrpt::poses::CPose3D got;
    m.getSensorPose(got);
    EXPECT_EQ(got, pose);
    m.field = {3, 4, 12};
    EXPECT_DOUBLE_EQ(m.magnitude(), 13.0);
}

// Writes the golden file for the current serialization version. Run by hand, once per new
// version (with a new file name), never to overwrite an existing golden file:
//   test_obs --gtest_also_run_disabled_tests --gtest_filter='*WriteGolden*'
TEST_F(MagnetometerTest, DISABLED_WriteGoldenV0) {
    const auto path = lodestone::test::testDataDir() / kGoldenV0;
    ASSERT_FALSE(std::filesystem::exists(path)) << "refusing to overwrite " << path;
    mrpt::io::CFileOutputStream file(path.string());
    mrpt::serialization::archiveFrom(file) << goldenV0Object();
}

TEST_F(MagnetometerTest, ABoolFieldHoldingAnotherByteIsARefusedRead) {
    // MRPT copies a stored bool's byte as it is; 127 would be an invalid bool (and was
    // exported as CALIBRATED=127). The payload ends ..., has_temperature, temperature,
    // calibrated, then MRPT's end-of-object marker.
    for (const auto& [fromEnd, field] : {std::pair<std::size_t, const char*>{2, "calibrated"},
                                         {11, "has_temperature"}}) {
        mrpt::io::CMemoryStream buffer;
        auto out = mrpt::serialization::archiveFrom(buffer);
        out << goldenV0Object();
        auto* bytes = static_cast<uint8_t*>(buffer.getRawBufferData());
        const std::size_t at = buffer.getTotalBytesCount() - fromEnd;
        ASSERT_EQ(bytes[at], 1) << field;
        bytes[at] = 127;
        buffer.Seek(0);
        try {
            mrpt::serialization::archiveFrom(buffer).ReadObject();
            ADD_FAILURE() << field << ": byte 127 read as a bool";
        } catch (const std::exception& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find(field), std::string::npos) << what;
            EXPECT_NE(what.find("127"), std::string::npos) << what;
        }
    }
}
