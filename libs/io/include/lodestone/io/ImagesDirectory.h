#pragma once

#include <string>

namespace lodestone::io {

/** The folder holding a rawlog's delay-loaded (external) images, by MRPT's convention: for
 * `dir/name.rawlog[.gz]` the first existing of `dir/name_Images`, `dir/name_images`,
 * `dir/name_IMAGES`, `dir/Images`; `dir/name_Images` if none exists. (MRPT 2.5's
 * CRawlog::detectImagesDirectory drops the path separator, hence our own.) */
std::string findImagesDirectory(const std::string& rawlogPath);

}  // namespace lodestone::io
