#pragma once

#include <lodestone/graphslam/gso/PoseGraphSolver.h>
#include <lodestone/odometry/FusedOdometry.h>
#include <mrpt/config/CConfigFileBase.h>

#include <deque>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace lodestone::graphslam::kidnap {

/** What KidnapDetector reads from [kidnap_detection]. */
struct KidnapDetectorParams {
    bool motion{false};   ///< the camera moves as the encoders do not (or the reverse)
    bool magnetic{false}; ///< the field changes while the wheels stand still
    double chi2{kChi2Planar999};   ///< VO vs wheels gate, 3 dof
    double floorSigmaXY{0.02};     ///< [m] model floor on their disagreement ...
    double floorSigmaYaw{2 * M_PI / 180};  ///< [rad] ... (VO's and the wheels' own errors)
    double floorRelative{0.05};    ///< ... plus this fraction of the window's travel and turn
    double riseFloor{0.05};        ///< [m] camera rise beyond 3 sigma + this: lifted
    double window{1.0};            ///< [s] VO and encoders compared over this much motion
    int persistence{3};            ///< inconsistent VO frames in a row before a lift is called
    double settle{0.5};            ///< [s] of wheels driving and agreeing VO: put down
    double magneticNoise{0.3};     ///< [uT] per reading (std of |B|)
    double magneticGateSigma{6};   ///< gate on the change of window means, in their sigmas
    double magneticWindow{0.3};    ///< [s] averaging window
    double stillStep{1e-4};        ///< [m] (and rad / 10) per frame: the wheels stand still
    /** [s] the node decider holds odometry back so a lift called late still cuts the edges
     * exactly where it happened. */
    double latency{1.5};
};

/** Kidnap detection for bases without a wheel-drop sensor: the robot is lifted
 * when
 *  - motion: over the last `window` seconds, visual odometry (chained through its reference
 *    frames) moved and the encoders did not (carried), or the encoders moved and VO did not
 *    (wheels in the air) — "moved" is a chi-square against zero under the claimed covariance
 *    plus absolute and relative floors, and the two must also disagree; or, the wheels standing
 *    still, the camera rose (a wheeled robot's camera stays at its height); for `persistence`
 *    VO frames in a row. Both moving but differently is a VO error, not a kidnap;
 *  - magnetic: the wheels stand still while the field magnitude (rotation-invariant) changes
 *    beyond the sensor noise between two windows.
 * It is put down when the wheels drive again for `settle` seconds and VO, where it has an
 * answer, agrees with them. Lift time: the first frame (or window) that disagreed. */
class KidnapDetector {
  public:
    using Params = KidnapDetectorParams;
    static Params readParams(const mrpt::config::CConfigFileBase& ini);

    struct Event {
        bool lifted{true};
        double time{0};  ///< [s] when it happened (not when it was detected)
        std::string by;  ///< "motion", "rise" or "magnetic"; put-downs say "wheels"
    };

    explicit KidnapDetector(Params p = {}) : params_(p) {}
    const Params& params() const { return params_; }
    bool enabled() const { return params_.motion || params_.magnetic; }

    /** One resolved odometry frame (in time order). */
    std::optional<Event> onFrame(const odometry::FusedOdometry::Estimate& e);
    /** One magnetometer reading: its time [s] and field magnitude [uT] (one sensor). */
    std::optional<Event> onMagnetic(double t, double magnitude);

    bool lifted() const { return lifted_; }
    struct Stats {
        std::size_t lifts{0}, byMotion{0}, byRise{0}, byMagnetic{0}, putDowns{0};
    };
    const Stats& stats() const { return stats_; }

  private:
    struct FrameState {
        mrpt::poses::CPose2D wheel;   // encoders composed since the start
        mrpt::poses::CPose2D visual;  // VO chained through its references (or the wheels)
        double wheelPositionVar{0}, wheelYawVar{0}, visualPositionVar{0}, visualYawVar{0};
        double height{0}, heightVar{0};  // the camera's rise, chained as VO
    };
    std::optional<Event> lift(double t, const char* by);

    Params params_;
    std::map<double, FrameState> frames_;  // recent frames, by timestamp
    FrameState last_;
    bool lifted_{false};
    int inconsistent_{0};
    double first_inconsistent_{0};
    std::optional<double> still_since_, driving_since_;
    double last_frame_time_{-1};
    std::deque<std::pair<double, double>> field_;  // (t, |B|) since the wheels stood still
    Stats stats_;
};

}  // namespace lodestone::graphslam::kidnap
