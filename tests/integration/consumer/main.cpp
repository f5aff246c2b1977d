// Serializes a magnetometer reading through MRPT and reads it back by class name.
#include <lodestone/obs/CObservationMagnetometer.h>
#include <lodestone/obs/registerAllClasses.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/serialization/CArchive.h>

#include <iostream>

int main() {
    lodestone::registerAllClasses();
    lodestone::obs::CObservationMagnetometer m;
    m.field = {20.0, -3.0, -44.0};
    mrpt::io::CMemoryStream buffer;
    auto archive = mrpt::serialization::archiveFrom(buffer);
    archive << m;
    buffer.Seek(0);
    auto back =
        std::dynamic_pointer_cast<lodestone::obs::CObservationMagnetometer>(archive.ReadObject());
    if (!back || back->field.z != -44.0) {
        std::cerr << "consumer: round trip failed\n";
        return 1;
    }
    std::cout << "consumer: lodestone::obs OK\n";
    return 0;
}
