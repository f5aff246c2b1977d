#include "MrptBytes.h"

#include <mrpt/io/CMemoryStream.h>
#include <mrpt/serialization/CArchive.h>

namespace lodestone::test {

namespace {
std::string bytesOf(const mrpt::io::CMemoryStream& buffer) {
    return std::string(static_cast<const char*>(buffer.getRawBufferData()), buffer.getTotalBytesCount());
}
}  // namespace

std::string serializedBytes(const mrpt::serialization::CSerializable& object) {
    mrpt::io::CMemoryStream buffer;
    auto out = mrpt::serialization::archiveFrom(buffer);
    out << object;
    return bytesOf(buffer);
}

std::string nullObjectBytes() {
    mrpt::io::CMemoryStream buffer;
    auto out = mrpt::serialization::archiveFrom(buffer);
    out << mrpt::serialization::CSerializable::Ptr();
    return bytesOf(buffer);
}

std::string framedObject(const std::string& className, int version, const std::string& body) {
    return std::string(1, static_cast<char>(0x80 | className.size())) + className +
           static_cast<char>(version) + body + static_cast<char>(0x88);
}

}  // namespace lodestone::test
