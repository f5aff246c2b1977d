#pragma once

#include <mrpt/serialization/CSerializable.h>

#include <string>

namespace lodestone::io::detail {

/** What is wrong with an entry MRPT read without complaint but that would crash or throw
 * where it is used: a null element of a sensory frame or action collection, an enum field
 * holding a value its type does not have (MRPT copies the raw integer; printing it throws).
 * Empty when nothing is. */
std::string damagedPart(const mrpt::serialization::CSerializable& entry);

}  // namespace lodestone::io::detail
