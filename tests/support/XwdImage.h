#pragma once

// Reads an X Window Dump (what `xwd -root` writes): the GUI tests screenshot an Xvfb display
// with it and check the picture, without an image-conversion package.

#include <opencv2/core.hpp>

#include <string>

namespace lodestone::test {

/** The image of an XWD file (ZPixmap, 24 or 32 bits per pixel, as Xvfb at depth 24 writes) as
 * BGR. Throws std::runtime_error naming the file for anything else. */
cv::Mat3b readXwd(const std::string& path);

/** How many distinct colours an image holds, counted on a 4x4-pixel grid (a blank or
 * single-colour screen has one or two). */
std::size_t distinctColours(const cv::Mat3b& image);

}  // namespace lodestone::test
