#pragma once

#include <string>

namespace lodestone::io {

/** `dir/name.rawlog.gz` -> `dir/name`: the stem beside which a rawlog's companions live
 * (`name.gt.tum`, `name.events.txt`, `name_Images/`). */
std::string rawlogStem(const std::string& rawlogPath);

/** True when the path asks for gzip compression (ends in ".gz"). */
bool isGzipPath(const std::string& path);

}  // namespace lodestone::io
