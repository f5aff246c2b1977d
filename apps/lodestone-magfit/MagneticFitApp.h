#pragma once

#include <iosfwd>

namespace lodestone::slamapp {

/** `lodestone-magfit RAWLOG [--config INI] [--sensor LABEL] [--mode invariant|vector]
 * [--stretch M] [--step M]`: fits the hyperparameters of MagneticGpERD's along-the-path GP
 * (sigma_f, length scale, sigma_n, sigma_c) to a recording by maximizing the log marginal
 * likelihood, and prints them as the INI lines to paste into [MagneticGpERD].
 * The path comes from the rawlog's CObservationOdometry poses (travel = odometry distance,
 * heading = odometry heading), the field from its CObservationMagnetometer readings; the
 * readings are resampled by distance and cut into stretches of `--stretch` metres.
 * Exit codes: 0 fitted; 1 bad input (file, INI, no readings, read fault - named); 2 usage. */
int runMagneticFitApp(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

}  // namespace lodestone::slamapp
