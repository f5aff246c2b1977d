#pragma once

#include <ostream>

namespace lodestone::view {

/** The `lodestone-view DIR` command line: the 3D scene of a lodestone-slam output folder or a
 * saved map folder, in MRPT's window, as an off-screen screenshot (--screenshot) or as a
 * .3Dscene file for MRPT's SceneViewer3D (--export). Exit codes: 0 ok, 1 bad input or no
 * display for the window, 2 usage. */
int runViewApp(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

}  // namespace lodestone::view
