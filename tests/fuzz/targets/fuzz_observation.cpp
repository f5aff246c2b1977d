// One of Lodestone's observation classes through MRPT's archive: the first byte picks the
// class, the second is the serialization version, the rest the object's body, read as a
// one-entry rawlog (RawlogReader: the apps' path, with its allocation bound). A body that
// reads must print and convert, and write back to bytes that read to the same bytes again
// (a round trip that changes the object is a finding: abort).
#include <lodestone/inspect/EntryText.h>
#include <lodestone/io/RawlogReadError.h>
#include <lodestone/io/RawlogReader.h>
#include <lodestone/obs/CObservationMagnetometer.h>
#include <lodestone/obs/CObservationWheelDrop.h>
#include <lodestone/obs/ImuMagnetometerConversion.h>
#include <lodestone/obs/registerAllClasses.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/serialization/CArchive.h>

#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>

#include "../FuzzInput.h"

namespace {
std::string bytesOf(const mrpt::serialization::CSerializable& object) {
    mrpt::io::CMemoryStream buffer;
    auto out = mrpt::serialization::archiveFrom(buffer);
    out << object;
    return std::string(static_cast<const char*>(buffer.getRawBufferData()), buffer.getTotalBytesCount());
}

mrpt::serialization::CSerializable::Ptr readBytes(const std::string& bytes) {
    mrpt::io::CMemoryStream buffer;
    buffer.assignMemoryNotOwn(bytes.data(), bytes.size());
    auto in = mrpt::serialization::archiveFrom(buffer);
    return in.ReadObject();
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace lodestone;
    registerAllClasses();
    if (size < 2) return 0;
    const std::string className = (data[0] & 1) ? obs::CObservationWheelDrop::className
                                                : obs::CObservationMagnetometer::className;
    std::string framed(1, static_cast<char>(0x80 | className.size()));
    framed += className;
    framed += static_cast<char>(data[1]);
    framed.append(reinterpret_cast<const char*>(data + 2), size - 2);
    framed += static_cast<char>(0x88);  // MRPT's end-of-object flag
    mrpt::serialization::CSerializable::Ptr object;
    try {
        io::RawlogReader reader(fuzz::writeScratch("observation.rawlog", framed));
        const auto entry = reader.next();
        if (!entry) return 0;
        object = entry->object;
    } catch (const io::RawlogReadError&) {
        return 0;
    }
    std::ostringstream text;
    inspect::describeEntry(*object, text);
    if (auto mag = std::dynamic_pointer_cast<obs::CObservationMagnetometer>(object)) {
        try {
            const auto imu = obs::imuFromMagnetometer(*mag);
            obs::magnetometerFromImu(*imu, obs::MagneticUnit::gauss());
        } catch (const std::exception&) {
        }
    }
    const std::string once = bytesOf(*object);
    const std::string twice = bytesOf(*readBytes(once));
    if (once != twice) {
        std::cerr << "fuzz_observation: " << className << " changed in a write-read-write round trip\n";
        std::abort();
    }
    return 0;
}
