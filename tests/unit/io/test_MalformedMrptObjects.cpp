// Stock MRPT objects whose deserializers trust what they read: a version-0/1
// CActionRobotMovement2D whose pose PDF is stored as "nullptr" made MRPT dereference a null
// pointer (SIGSEGV in lodestone-inspect, -slam, -magfit and MRPT's own rawlog-edit); a null
// element inside a sensory frame or action collection crashed whoever walked it next. Each
// must be a read error naming the entry; well-formed old versions must read as MRPT reads them.
#include <gtest/gtest.h>
#include <lodestone/io/RawlogReader.h>
#include <lodestone/io/RawlogSource.h>
#include <lodestone/obs/registerAllClasses.h>
#include <mrpt/obs/CObservationImage.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/poses/CPosePDFGaussian.h>


#include "MrptBytes.h"
#include "RawlogTestHelpers.h"
#include "SampleObservations.h"
#include "TestPaths.h"

using namespace lodestone;

namespace {
using test::framedObject;
using test::nullObjectBytes;
using test::rawBytes;
using test::serializedBytes;

/** A version 0 or 1 CActionRobotMovement2D: the PDF object, the method, then (version 1)
 * velocities and encoder ticks. */
std::string oldMovement(int version, const std::string& pdf) {
    std::string body = pdf + rawBytes<std::int32_t>(0 /* emOdometry */);
    if (version == 1) {
        body += rawBytes<std::uint8_t>(1) + rawBytes(0.5f) + rawBytes(0.25f) + rawBytes<std::uint8_t>(1) +
                rawBytes<std::int32_t>(10) + rawBytes<std::int32_t>(-5);
    }
    return framedObject("CActionRobotMovement2D", version, body);
}

std::string actions(const std::vector<std::string>& members) {
    std::string body = rawBytes<std::uint32_t>(static_cast<std::uint32_t>(members.size()));
    for (const auto& m : members) body += m;
    return framedObject("CActionCollection", 0, body);
}

std::string gaussianPdf(double x, double y, double phi) {
    mrpt::poses::CPosePDFGaussian pdf;
    pdf.mean = mrpt::poses::CPose2D(x, y, phi);
    pdf.cov.setIdentity();
    return serializedBytes(pdf);
}

std::string firstEntryError(const std::string& path) {
    io::RawlogReader reader(path);
    try {
        reader.next();
    } catch (const io::RawlogReadError& e) {
        EXPECT_EQ(e.entryIndex(), 0u);
        return e.what();
    }
    return {};
}
}  // namespace

TEST(MalformedMrptObjects, ANullPosePdfInAnOldOdometryActionIsAReadError) {
    registerAllClasses();
    test::TempDir dir;
    for (int version : {0, 1}) {
        const auto path = dir.file("null_pdf_v" + std::to_string(version) + ".rawlog");
        test::writeBytes(path, actions({oldMovement(version, nullObjectBytes())}));
        const std::string error = firstEntryError(path);
        EXPECT_NE(error.find(path), std::string::npos) << error;
        EXPECT_NE(error.find("pose PDF is missing"), std::string::npos) << error;
    }
}

TEST(MalformedMrptObjects, APdfOfTheWrongClassIsAReadError) {
    registerAllClasses();
    test::TempDir dir;
    const auto path = dir.file("wrong_pdf.rawlog");
    mrpt::obs::CObservationOdometry notAPdf;
    test::writeBytes(path, actions({oldMovement(1, serializedBytes(notAPdf))}));
    EXPECT_NE(firstEntryError(path).find("not a CPosePDF"), std::string::npos);
}

TEST(MalformedMrptObjects, ANonOdometryActionWithoutAPdfIsAReadError) {
    // Versions >= 2: the method first; anything but odometry is followed by the PDF object.
    registerAllClasses();
    test::TempDir dir;
    const int version = 7;  // MRPT 2.5's
    for (const auto& pdf : {nullObjectBytes(), serializedBytes(mrpt::poses::CPose2D(1, 2, 0))}) {
        const auto path = dir.file("no_pdf.rawlog");
        const std::string body = rawBytes<std::int32_t>(1 /* emScan2DMatching */) + pdf + rawBytes<std::uint8_t>(0) +
                                 rawBytes(0.0) + rawBytes(0.0) + rawBytes<std::uint8_t>(0) + rawBytes<std::int32_t>(0) +
                                 rawBytes<std::int32_t>(0) + rawBytes<std::uint64_t>(0);
        test::writeBytes(path, actions({framedObject("CActionRobotMovement2D", version, body)}));
        EXPECT_NE(firstEntryError(path).find("pose PDF is missing"), std::string::npos);
    }
}

TEST(MalformedMrptObjects, CurrentActionsReadBackUnchanged) {
    // Through the guards, what MRPT writes reads back to the same bytes: odometry (PDF rebuilt
    // from the increment) and a scan-matching estimate (PDF stored).
    registerAllClasses();
    test::TempDir dir;
    mrpt::obs::CActionRobotMovement2D odometry;
    odometry.computeFromOdometry(mrpt::poses::CPose2D(0.2, 0.01, 0.1), {});
    odometry.hasEncodersInfo = true;
    odometry.encoderLeftTicks = 7;
    mrpt::obs::CActionRobotMovement2D matched;
    matched.estimationMethod = mrpt::obs::CActionRobotMovement2D::emScan2DMatching;
    mrpt::poses::CPosePDFGaussian pdf;
    pdf.mean = mrpt::poses::CPose2D(0.5, -0.2, 0.3);
    pdf.cov.setIdentity();
    matched.poseChange = mrpt::poses::CPosePDF::Ptr(std::make_shared<mrpt::poses::CPosePDFGaussian>(pdf));
    for (const auto* move : {&odometry, &matched}) {
        mrpt::obs::CActionCollection written;
        written.insert(*move);
        const auto path = dir.file("current.rawlog");
        test::writeBytes(path, serializedBytes(written));
        io::RawlogReader reader(path);
        const auto entry = reader.next();
        ASSERT_TRUE(entry);
        EXPECT_EQ(serializedBytes(*entry->object), serializedBytes(written));
    }
}

TEST(MalformedMrptObjects, WellFormedOldVersionsReadAsMrptDefinesThem) {
    registerAllClasses();
    test::TempDir dir;
    for (int version : {0, 1}) {
        const auto path = dir.file("old_v" + std::to_string(version) + ".rawlog");
        test::writeBytes(path, actions({oldMovement(version, gaussianPdf(0.3, -0.1, 0.2))}));
        io::RawlogReader reader(path);
        const auto entry = reader.next();
        ASSERT_TRUE(entry);
        const auto collection = std::dynamic_pointer_cast<mrpt::obs::CActionCollection>(entry->object);
        ASSERT_TRUE(collection);
        ASSERT_EQ(collection->size(), 1u);
        const auto& action = *collection->get(0);
        // What MRPT's tools see: the stock class, by runtime id and by name.
        EXPECT_TRUE(IS_CLASS(action, mrpt::obs::CActionRobotMovement2D));
        EXPECT_STREQ(action.GetRuntimeClass()->className, "mrpt::obs::CActionRobotMovement2D");
        const auto& move = dynamic_cast<const mrpt::obs::CActionRobotMovement2D&>(action);
        ASSERT_TRUE(move.poseChange);
        EXPECT_DOUBLE_EQ(move.rawOdometryIncrementReading.x(), 0.3);
        EXPECT_DOUBLE_EQ(move.rawOdometryIncrementReading.y(), -0.1);
        EXPECT_NEAR(move.rawOdometryIncrementReading.phi(), 0.2, 1e-12);
        if (version == 1) {
            EXPECT_TRUE(move.hasVelocities);
            EXPECT_DOUBLE_EQ(move.velocityLocal.vx, 0.5);
            EXPECT_DOUBLE_EQ(move.velocityLocal.omega, 0.25);
            EXPECT_TRUE(move.hasEncodersInfo);
            EXPECT_EQ(move.encoderLeftTicks, 10);
            EXPECT_EQ(move.encoderRightTicks, -5);
        } else {
            EXPECT_FALSE(move.hasEncodersInfo);
        }
        // Written again, it is a stock object of the current version.
        const std::string again = serializedBytes(move);
        EXPECT_NE(again.find("CActionRobotMovement2D"), std::string::npos);
        EXPECT_FALSE(reader.next());
    }
}

TEST(MalformedMrptObjects, AnOldActionCutShortIsAReadError) {
    registerAllClasses();
    test::TempDir dir;
    const auto path = dir.file("short.rawlog");
    std::string bytes = actions({oldMovement(1, gaussianPdf(0.1, 0, 0))});
    bytes.resize(bytes.size() - 12);
    test::writeBytes(path, bytes);
    EXPECT_FALSE(firstEntryError(path).empty());
}

TEST(MalformedMrptObjects, NullElementsOfContainersAreReadErrors) {
    registerAllClasses();
    test::TempDir dir;
    const auto actionsPath = dir.file("null_action.rawlog");
    test::writeBytes(actionsPath, actions({nullObjectBytes()}));
    EXPECT_NE(firstEntryError(actionsPath).find("action 0 is null"), std::string::npos);

    const auto framePath = dir.file("null_observation.rawlog");
    test::writeBytes(framePath, framedObject("CSensoryFrame", 2, rawBytes<std::uint32_t>(1) + nullObjectBytes()));
    const std::string error = firstEntryError(framePath);
    EXPECT_NE(error.find("observation 0 of the sensory frame is null"), std::string::npos) << error;
}

TEST(MalformedMrptObjects, ADamagedJpegImageIsAReadErrorNotAnExit) {
    // libjpeg's default error handler calls exit(1); MRPT decodes embedded JPEGs with it. The
    // executable's jpeg_std_error (libs/io/hooks) makes it throw: a read error, the entries
    // before it delivered. (Without the hook this test binary would exit here.)
    registerAllClasses();
    test::TempDir dir;
    const bool wasDisabled = mrpt::img::CImage::DISABLE_JPEG_COMPRESSION();
    mrpt::img::CImage::DISABLE_JPEG_COMPRESSION(false);
    mrpt::obs::CObservationImage photo;
    photo.image = mrpt::img::CImage(64, 48, mrpt::img::CH_RGB);
    photo.image.filledRectangle(0, 0, 63, 47, mrpt::img::TColor(200, 40, 10));
    std::string image = serializedBytes(photo);
    mrpt::img::CImage::DISABLE_JPEG_COMPRESSION(wasDisabled);
    const auto soi = image.find("\xFF\xD8\xFF");
    ASSERT_NE(soi, std::string::npos) << "MRPT did not store the image as JPEG";
    image.replace(soi, 3, std::string(3, '\0'));
    const auto path = dir.file("damaged_jpeg.rawlog");
    test::writeBytes(path, serializedBytes(*test::makeMagnetometer(1.0, "MAG", 1)) + image);
    io::RawlogReader reader(path);
    EXPECT_TRUE(reader.next());
    try {
        reader.next();
        ADD_FAILURE() << "the damaged image was read";
    } catch (const io::RawlogReadError& e) {
        EXPECT_EQ(e.entryIndex(), 1u);
        EXPECT_NE(std::string(e.what()).find("CImage: JPEG image: Not a JPEG file"), std::string::npos) << e.what();
    }
}

TEST(MalformedMrptObjects, FieldsMrptCopiesWithoutCheckingAreValidated) {
    // An enum holding a value its type lacks (printing it throws inside MRPT) and a bool byte
    // that is neither 0 nor 1 (undefined behaviour where it is read): corrupt entries.
    registerAllClasses();
    test::TempDir dir;
    auto scan = test::makeRangeScan(1.0, 8, 6, 1.0);
    scan->intensityImageChannel = static_cast<mrpt::obs::CObservation3DRangeScan::TIntensityChannelID>(7);
    const auto scanPath = dir.file("channel.rawlog");
    test::writeBytes(scanPath, serializedBytes(*scan));
    EXPECT_NE(firstEntryError(scanPath).find("intensity channel id 7"), std::string::npos);

    // The flag byte is where two objects that differ only in it differ.
    mrpt::obs::CObservationOdometry odometry;
    const std::string without = serializedBytes(odometry);
    odometry.hasEncodersInfo = true;
    std::string bytes = serializedBytes(odometry);
    const auto odoPath = dir.file("flag.rawlog");
    std::size_t at = 0;
    while (at < without.size() && without[at] == bytes[at]) ++at;
    ASSERT_EQ(bytes[at], '\x01');
    bytes[at] = 8;
    test::writeBytes(odoPath, bytes);
    EXPECT_NE(firstEntryError(odoPath).find("neither 0 nor 1"), std::string::npos);
}
