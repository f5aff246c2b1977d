// Harder variants of a magnetic recording, for benches and tests: what a method tuned on the
// walks at hand meets elsewhere - a quieter building, another unit, another rate, a noisier sensor.
//   quiet:A      the field's deviation from its mean (in the world frame) scaled by A, and white
//                noise added back so that readings at one place differ between passes as much
//                as before: variance (1 - A^2) sigma_rep^2 per component, sigma_rep the
//                recording's own repeatability (passRepeatability), at least kRepeatabilityFloor
//   gauss, normalized:F   written as a Kok-layout CSV in that unit and read back with it (the
//                user's path: lodestone-import --unit), F the field strength of the normalization
//   rate:HZ      resampled in time (positions, headings and the world-frame field interpolated)
//   noise:S      white noise of S uT per component added
// Every draw is seeded (the run's seed): a variant is the same bytes for the same seed.
#pragma once

#include <lodestone/datasets/MagneticRecording.h>

#include <string>

namespace lodestone::datasets {

/** Per component [uT]: the repeatability a quieter variant keeps at least, where a recording
 * repeats better than real ones (the synthetic walks repeat exactly). */
constexpr double kRepeatabilityFloor = 0.6;

/** How readings at one place differ between passes, per component [uT]: from every pair of
 * readings within `radius` of each other by the reference positions and more than `gap` metres
 * of walk apart, the world-frame differences' robust spread (1.4826 MAD) over sqrt 2. NaN where
 * no place is revisited. */
double passRepeatability(const MagneticRecording& recording,
                         double radius = 0.15, double gap = 5.0);

/** `recording` made into the variant `spec` (above; "" or "original": as it is). `scratch` is a
 * folder for the unit variants' CSV. Throws std::invalid_argument on an unknown spec. */
MagneticRecording magneticVariant(
    const MagneticRecording& recording, const std::string& spec,
    unsigned seed, const std::string& scratch);

}  // namespace lodestone::datasets
