#pragma once

#include <lodestone/odometry/DiffDriveOdometry.h>
#include <lodestone/odometry/PlanarFusion.h>
#include <lodestone/odometry/PreparedFrames.h>
#include <lodestone/vision/RgbdVisualOdometry.h>
#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/obs/CObservation.h>

#include <Eigen/Geometry>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <vector>

namespace lodestone::odometry {

/** The odometry front end: wheel encoders (CObservationOdometry with ticks) and RGB-D frames
 * (CObservation3DRangeScan) in time order in, one planar pose per camera frame out, for one or
 * several fusion methods at once (so they can be compared on the same VO run).
 *
 * Synchronization: a frame's wheel motion is the encoder travel interpolated at the frame's
 * timestamp, so a frame is resolved when the first encoder sample after it arrives. VO motion
 * (optical frame) is moved to the robot frame with the camera's sensorPose and projected on
 * SE(2). When VO matched against an older reference (frames in between failed), its motion is
 * re-based onto each method's own pose at that reference.
 *
 * Pose-only odometry (CObservationOdometry without encoder ticks: a base that reports its
 * integrated pose, or the synthesized odometry of `lodestone-import aalto|kok`) is taken as it
 * is: every sample gives an estimate, its increment being the pose change with the
 * per-sample variances `pose_position_noise` / `pose_heading_noise`, the same for every
 * method. Such a source drives the estimates on its own; RGB-D frames that come with it are
 * counted and not fused (framesIgnored()). */
class FusedOdometry {
  public:
    struct Params : public mrpt::config::CLoadableOptions {
        DiffDriveOdometry::Params wheels;           ///< INI section [wheel_odometry]
        vision::RgbdVisualOdometry::Params visual;  ///< INI section [visual_odometry]
        std::string method{"covariance"};           ///< [odometry_fusion] method
        double kalmanWeight{0.7};             ///< C of paper 003 eq. (2): weight of the wheels
        double kalmanProcessNoise{0.5};       ///< constant-velocity model [unit^2/s^3]
        double kalmanMeasurementNoise{1e-4};  ///< blended-position variance [m^2 or rad^2]
        std::string encoderLabel;             ///< only this odometry label ("" = any)
        std::string cameraLabel;              ///< only this RGB-D label ("" = any)
        double posePositionNoise{1e-4};  ///< pose-only odometry: variance per sample and axis [m^2]
        double poseHeadingNoise{1e-4};   ///< pose-only odometry: variance per sample [rad^2]
        /** The wheels' prediction that guides VO's matching is planar; the floor tilts and
         * lifts the camera this much (1 sigma) between VO's reference and the frame. */
        double guidedTiltSigma{1.0 * M_PI / 180};  ///< [rad] roll and pitch
        double guidedRiseSigma{0.01};              ///< [m]

        /** Reads [wheel_odometry], [visual_odometry] and [odometry_fusion] (`section` is the
         * fusion one). */
        void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                                const std::string& section) override;
        void dumpToTextStream(std::ostream& out) const override;
    };

    /** One camera frame's outcome. */
    struct Estimate {
        double timestamp{0};                               ///< [s]
        std::vector<mrpt::poses::CPosePDFGaussian> poses;  ///< one per method, in order
        /** Per method: the motion since the previous frame with its covariance (zero on the
         * first frame). Composing them gives `poses`; a pose graph takes these. */
        std::vector<mrpt::poses::CPosePDFGaussian> increments;
        /** Per method: how each increment moves with the wheels' scales (x, y, phi by left,
         * right: DiffDriveOdometry::scaleJacobian through the fusion's gain on the wheels;
         * zero without encoders). */
        std::vector<Eigen::Matrix<double, 3, 2>> wheelScale;
        vision::VoResult visual;
        /** The frame's own wheel step (encoders alone; zero on the first frame). */
        mrpt::poses::CPosePDFGaussian wheel;
        /** When VO succeeded: the robot's motion since VO's reference frame
         * (visual.referenceTimestamp), planar part with covariance, and how far the robot rose
         * [m] with its variance: a wheeled robot does not rise (kidnap detection). */
        std::optional<mrpt::poses::CPosePDFGaussian> visualSinceReference;
        double visualRise{0}, visualRiseVariance{0};
    };

    /** `methods` defaults to {params.method}. */
    explicit FusedOdometry(const Params& params, std::vector<std::string> methods = {});

    /** Feeds one observation; returns the frames it resolved (usually zero or one). Other
     * observation classes are ignored. */
    std::vector<Estimate> process(const mrpt::obs::CObservation::Ptr& obs);
    /** Resolves frames still waiting for a later encoder sample (at the end of the data). */
    std::vector<Estimate> flush();

    const std::vector<std::string>& methods() const { return method_names_; }
    const vision::RgbdVisualOdometry& visual() const { return visual_; }
    /** The camera's frames, preparable ahead on other threads (PreparedFrames::prepareAhead). */
    PreparedFrames& preparedFrames() { return prepared_; }
    const PreparedFrames& preparedFrames() const { return prepared_; }
    std::size_t framesProcessed() const { return frames_; }
    std::size_t poseSamples() const { return pose_samples_; }
    std::size_t framesIgnored() const { return frames_ignored_; }

  private:
    struct Pending {
        double t;
        vision::VoResult vo;
        Eigen::Isometry3d T_robot_optical;
    };
    struct WheelSample {
        double t, left, right;  // cumulative wheel travels [m]
    };
    Eigen::Vector2d travelAt(double t) const;
    Estimate resolve(const Pending& p);
    /** The wheels' prediction of the frame at `t` relative to VO's reference frame, in the
     * optical frame (for guided matching); none without encoder samples around both. */
    std::optional<vision::MotionPrior> wheelPrior(double t,
                                                  const Eigen::Isometry3d& T_robot_optical) const;
    Estimate fromPoseSample(double t, const mrpt::poses::CPose2D& pose);
    /** VO's motion in the robot frame, projected on the plane; `rise` / `riseVariance`, when
     * given, get its vertical part. */
    mrpt::poses::CPosePDFGaussian visualOnRobot(const Pending& p, double* rise = nullptr,
                                                double* riseVariance = nullptr) const;

    Params params_;
    std::vector<std::string> method_names_;
    std::vector<std::unique_ptr<PlanarFusion>> fusions_;
    std::vector<std::map<double, mrpt::poses::CPose2D>> recent_;  // per method: frame time -> pose
    DiffDriveOdometry wheels_;
    vision::RgbdVisualOdometry visual_;
    PreparedFrames prepared_{[this](vision::RgbdFrame f) { return visual_.prepare(std::move(f)); }};
    std::deque<WheelSample> wheel_history_;
    std::deque<Pending> pending_;
    double cum_left_{0}, cum_right_{0};
    std::optional<double> last_frame_time_;
    Eigen::Vector2d last_frame_travel_{0, 0};
    std::size_t frames_{0};
    std::optional<mrpt::poses::CPose2D> last_pose_sample_;
    mrpt::poses::CPosePDFGaussian pose_estimate_;  // pose-only odometry composed
    std::size_t pose_samples_{0}, frames_ignored_{0};
    double oldest_reference_{0};  // frames before it cannot be VO's reference any more
};

}  // namespace lodestone::odometry
