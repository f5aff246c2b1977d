#pragma once

#include <lodestone/datasets/MagneticRecording.h>
#include <mrpt/poses/CPose2D.h>

#include <cstdint>
#include <vector>

namespace lodestone::datasets {

/** Kok & Solin's odometry drift model, for recordings without wheel odometry: at each
 * odometry sample the body-frame position increment of the reference gets Gaussian noise of
 * variance `sp2` per axis, and the heading increment a rate bias plus Gaussian noise of
 * variance `sh2`. The defaults are theirs for these walks. */
struct OdometryDriftModel {
    std::uint64_t seed{1};
    double bias{0.005};  ///< heading rate bias [rad/s]
    double sp2{1e-4};    ///< position noise variance per sample and axis [m^2]
    double sh2{1e-4};    ///< heading noise variance per sample [rad^2]
    /** Odometry samples per second: the recording's sample nearest each 1/rate tick (Kok's
     * walks are 10 Hz, so all of them at 10; Aalto's 50 Hz every fifth). 0: every sample. */
    double rate{10};
};

struct SyntheticOdometrySample {
    std::size_t index{0};  ///< the recording sample it was taken at
    double t{0};
    mrpt::poses::CPose2D pose;  ///< integrated odometry, starting at the origin
};

/** The odometry the model gives along `recording`'s reference trajectory (deterministic for a
 * seed). Throws std::invalid_argument for a negative variance, bias that is not finite or a
 * negative rate. */
std::vector<SyntheticOdometrySample> synthesizeOdometry(const MagneticRecording& recording,
                                                        const OdometryDriftModel& model);

}  // namespace lodestone::datasets
