#pragma once
// MRPT's serialization format as bytes, for tests and the fuzz seed tool that build damaged
// objects by hand.
#include <mrpt/serialization/CSerializable.h>

#include <cstring>
#include <string>

namespace lodestone::test {

/** What `archive << object` writes: the framed object. */
std::string serializedBytes(const mrpt::serialization::CSerializable& object);

/** A null object pointer as MRPT writes it (class "nullptr"). */
std::string nullObjectBytes();

/** MRPT's object framing around a hand-made body: name length | 0x80, the name, the version;
 * the body; the end flag 0x88. */
std::string framedObject(const std::string& className, int version, const std::string& body);

/** A value's bytes (little-endian on this machine, as MRPT writes them). */
template <typename T>
std::string rawBytes(T value) {
    std::string s(sizeof(T), '\0');
    std::memcpy(s.data(), &value, sizeof(T));
    return s;
}

}  // namespace lodestone::test
