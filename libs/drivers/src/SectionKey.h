#pragma once

#include <string>

namespace lodestone::drivers::detail {

/** How a driver names a key of its INI section in errors. Not "[SECTION] key": MRPT's
 * loadConfig() rethrows with the text parsed for a "[location]". */
inline std::string sectionKey(const std::string& section, const char* key) {
    return "sensor section '" + section + "', key '" + key + "'";
}

}  // namespace lodestone::drivers::detail
