#pragma once

#include <string>

namespace lodestone::io {

/** MRPT's exception text (a block per nested object or call, each with a backtrace) as one line
 * a user can read: the chain of classes being read and the innermost message,
 * "CActionCollection > CPosePDFGaussian: <message>"; text not in MRPT's format: its first line. */
std::string condensedMrptError(const std::string& text);

}  // namespace lodestone::io
