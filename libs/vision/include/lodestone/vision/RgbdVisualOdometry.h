#pragma once

#include <lodestone/vision/DescriptorMatcher.h>
#include <lodestone/vision/GuidedMatcher.h>
#include <lodestone/vision/OrbFeatures.h>
#include <lodestone/vision/PreparedFrame.h>
#include <lodestone/vision/RgbdFrame.h>
#include <lodestone/vision/RigidRansac.h>
#include <lodestone/vision/depth/PointToPlaneIcp.h>
#include <mrpt/config/CLoadableOptions.h>

#include <array>
#include <cmath>
#include <memory>
#include <functional>
#include <optional>

namespace lodestone::vision {

/** Where the odometry stands. */
enum class VoState {
    Initializing,  ///< no reference frame yet (or just re-initialized after LOST)
    Tracking,      ///< the last frames were aligned
    Lost           ///< `lostAfter` consecutive frames failed; no motion is reported
};

/** Why a frame did not give a motion (`FasterThanCarrier`: the motion since the last tracked
 * frame is more than the carrier can do in the time between them). */
enum class VoFailure {
    None,
    NoReference,
    FewFeatures,
    FewMatches,
    NoConsensus,
    Implausible,
    FasterThanCarrier
};

const char* toString(VoState s);
const char* toString(VoFailure f);

/** Time spent on one frame [ms], by step. */
struct VoTiming {
    double orb{0}, matching{0}, ransac{0};
    double depth{0};  ///< sampling the depth cloud and, where features failed, aligning it
};

/** Time summed over every frame processed [ms], by step. */
struct VoTotals {
    std::size_t frames{0};
    VoTiming ms;
    std::size_t guided{0};          ///< frames aligned by matching guided by a motion prior
    std::size_t guidedFallback{0};  ///< frames with a prior whose guided match failed (brute force then)
    /** Descriptor pairs the guided matcher compared, against the n x m brute force would. */
    double guidedPairsCompared{0}, guidedPairsAll{0};
    std::size_t depthAligned{0};  ///< frames whose features failed and whose depth aligned
    std::size_t depthTried{0};    ///< frames whose features failed and whose depth was tried
    std::size_t depthJoined{0};   ///< frames whose features and depth were solved as one
    /** ... of those, the ones whose features and depth disagreed beyond their covariances
     * (DepthAlignment::disagreed: the covariance was widened). */
    std::size_t depthJoinedDisagreeing{0};
    /** Why depth alignment failed, by DepthAlignFailure (None: it aligned, implausibly). */
    std::array<std::size_t, 4> depthFailures{};
    /** Frames tried, by the number of directions the depth pinned (0..6). */
    std::array<std::size_t, 7> depthObserved{};
};

/** A rotation another sensor measured between the reference frame and this one (a gyro's,
 * moved into the optical frame): R_ref_cur and its per-axis sigma [rad]; and how far the
 * carrier may have moved meanwhile, per axis [m] (0: unknown - the rotation only starts the
 * depth alignment). */
struct RotationPrior {
    Eigen::Matrix3d R_ref_cur{Eigen::Matrix3d::Identity()};
    double sigma{0.01};
    double translationSigma{0};
    /** How long the carrier's velocity persists where nothing measures it [s]: the translation
     * the depth does not pin follows the last measured velocity, fading with this time
     * constant (a first-order Gauss-Markov velocity, as odometry::FadingVelocity). */
    double velocitySeconds{1.0};
    /** The vertical in the reference's optical frame (zero: not known), for a rotation that
     * joins the features only in tilt (Params::GyroJoin::Tilt). */
    Eigen::Vector3d vertical{Eigen::Vector3d::Zero()};
};

/** What one frame gave. */
struct VoResult {
    bool success{false};  ///< a motion was estimated for this frame
    VoState state{VoState::Initializing};
    VoFailure failure{VoFailure::None};
    /** Pose of this frame in the reference frame's optical frame: p_ref = T p_cur. */
    Eigen::Isometry3d T_ref_cur{Eigen::Isometry3d::Identity()};
    Eigen::Matrix<double, 6, 6> covariance{
        Eigen::Matrix<double, 6, 6>::Identity()};  ///< see RigidEstimate
    double referenceTimestamp{0};  ///< [s] of the reference frame T_ref_cur is relative to
    std::size_t features{0}, matches{0}, inliers{0};
    /** The motion was found by matching guided by the caller's prior (else by brute force). */
    bool guided{false};
    /** The features failed and the motion is depth alignment's (`covariance` loose along what
     * the depth did not pin, `depthObserved` < 6); `failure` says why the features failed. */
    bool depthAligned{false};
    int depthObserved{0};
    /** The features aligned and the depth was solved with them (`depthWithFeatures`). */
    bool depthJoined{false};
    bool depthDisagreed{false};  ///< joined, and DepthAlignment::disagreed
    /** The features aligned and the caller's rotation (a gyro's) joined them
     * (`gyroWithFeatures`): `T_ref_cur` and `covariance` are the joined motion's, and these
     * the camera's own before it (for whoever learns the gyro's bias from them). Otherwise
     * the same as `T_ref_cur` and `covariance`. */
    bool gyroJoined{false};
    Eigen::Isometry3d T_ref_cur_camera{Eigen::Isometry3d::Identity()};
    Eigen::Matrix<double, 6, 6> covariance_camera{Eigen::Matrix<double, 6, 6>::Identity()};
    /** This frame's features (optical frame), for whoever keeps keyframes (the SLAM node
     * decider, loop closers). */
    std::shared_ptr<const FrameFeatures> frameFeatures;
    VoTiming timing;
};

/** RGB-D visual odometry as paper 001 §3: ORB features of the current frame are matched
 * against the reference frame, 3D-3D pairs aligned by SVD inside RANSAC. On success the current
 * frame becomes the reference once it is far enough from it (a keyframe); a frame that fails (too
 * few features, matches or inliers, or an implausible jump) leaves the reference as it was and
 * counts as lost; after `lostAfter` consecutive failures the state is LOST and the next frame
 * re-initializes. A frame with no depth, no features (a plain wall) or NaNs simply fails. */
class RgbdVisualOdometry {
  public:
    struct Params : public mrpt::config::CLoadableOptions {
        OrbExtractor::Params orb;
        DescriptorMatcher::Params matcher;
        RigidRansac::Params ransac;
        int lostAfter{5};            ///< consecutive failed frames before LOST
        /** From the reference (a frame's motion since its reference keyframe), beyond it the
         * motion is implausible [m] ... */
        double maxTranslation{0.5};
        double maxRotation{35 * M_PI / 180};  ///< ... [rad]
        /** Since the last tracked frame: a motion the carrier cannot make in the time between
         * them, `maxSpeed` times that time plus `stepError` (what one VO step may be off by),
         * is implausible [m/s, m] (0: no such check). An alignment of features along one edge
         * can jump tens of centimetres in one frame and claim a millimetre. */
        double maxSpeed{0};
        double stepError{0.05};
        double maxTurnRate{0};                ///< [rad/s] (0: no such check) ...
        double stepErrorAngle{3 * M_PI / 180};  ///< ... plus this [rad]
        /** A tracked frame replaces the reference only once it moved this far from it [m] or
         * turned this much [rad]: fewer, longer steps accumulate less error. 0, 0: every frame. */
        double keyframeDistance{0.10};
        double keyframeAngle{5 * M_PI / 180};
        /** What decides that a frame becomes the reference. `Measured`: its own motion, as
         * measured. A frame whose error happens to lengthen its step crosses the spacing a frame
         * early, and its error stays in the chain: the chosen steps are long by about a step's
         * noise (docs/results/camera-only.md). `Predicted`: the motion known before the frame is
         * measured (the caller's prior, else the last tracked frame's - a frame late; a gyro's
         * rotation), so the choice is blind to the frame's own error; a frame measured beyond
         * twice the spacing still becomes one (the next frames need the overlap). */
        enum class KeyframeBy { Measured, Predicted };
        KeyframeBy keyframeBy{KeyframeBy::Measured};
        std::uint64_t seed{1};  ///< RANSAC seed (deterministic results)
        /** With a motion prior, match each reference feature only against the keypoints in
         * its predicted gate (GuidedMatcher); brute force when that fails. */
        bool guidedMatching{true};
        double guidedGateChi2{11.83};      ///< the gate, chi-square with 2 dof
        double guidedKeypointSigma{1.0};  ///< ORB keypoint noise at level 0 [px]
        /** Where the features fail, align the frame's depth with the last keyframes' (point-to-
         * plane ICP from the caller's prior or constant velocity; PointToPlaneIcp). */
        bool depthAlignment{false};
        /** With depth alignment, also where the features aligned: both solved as one (the
         * features' motion and covariance as a measurement in the depth's Gauss-Newton). */
        bool depthWithFeatures{false};
        /** With depth alignment, a frame with too few features to start from starts it from
         * its depth alone (for a carrier whose wheels measure what depth leaves unpinned: a
         * plain corridor's length); false: VO starts only where features are. */
        bool depthStart{false};
        /** Where the features fail and a rotation prior says how far the carrier may have
         * moved: the depth and the rotation solved as one (the rotation and the fading
         * velocity's translation a measurement, loose by `translationSigma`), the motion counting when the
         * depth pins this many directions (3: a plain wall - with the rotation, 4 of 6
         * measured); 0: the rotation only starts the alignment. */
        int gyroDepthMinObserved{0};
        /** Where the features aligned and a rotation prior is given, the rotation joins their
         * motion as a measurement (joinRotation): a gyro pins the turn that far features
         * trade against a shift along the view. `Tilt`: only about the horizontal axes (the
         * prior's `vertical` left free) - a gyro's bias error is shared by every step, and
         * about the vertical nothing bounds what it adds up to, while the tilt is held at each
         * node by the accelerometer's up. */
        enum class GyroJoin { Off, Tilt, All };
        GyroJoin gyroWithFeatures{GyroJoin::Off};
        int depthModelKeyframes{1};  ///< keyframes in the local model depth aligns with (1: see docs/results/camera-only.md)
        DepthSampling depthSampling;  ///< `depth_grid_columns`, `depth_points_from_cell_mean`; noise from RANSAC's
        PointToPlaneIcp::Params depthIcp;

        /** All keys in one section (ORB, matcher and RANSAC keys included). */
        void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                                const std::string& section) override;
        void dumpToTextStream(std::ostream& out) const override;
    };

    RgbdVisualOdometry();
    explicit RgbdVisualOdometry(const Params& params);

    /** Processes the next frame. With a `prior` (where the frame is relative to the current
     * reference, `referenceTimestamp()`) and `guidedMatching`, matching is guided by it. With
     * a `rotation` (a gyro's since the reference), depth alignment where the features fail
     * starts from it, and with `gyroWithFeatures` it joins the features' motion. */
    VoResult process(const RgbdFrame& frame, const MotionPrior* prior = nullptr,
                     const RotationPrior* rotation = nullptr);
    /** The same, for a frame prepare() prepared (on this thread or another). */
    VoResult process(PreparedFrame frame, const MotionPrior* prior = nullptr,
                     const RotationPrior* rotation = nullptr);
    /** What process() computes from the frame alone: its ORB features and, with depth
     * alignment, its depth cloud. Thread-safe (it touches nothing process() changes), so a
     * reader may prepare the next frames while this one is processed. */
    PreparedFrame prepare(RgbdFrame frame) const;
    /** The timestamp of the frame the next one will be aligned with, if any. */
    std::optional<double> referenceTimestamp() const;

    /** Two frames' features aligned as `process` aligns a frame with its reference (matching,
     * RANSAC; no plausibility gate on the motion, no state change): `estimate.transform` is
     * the current frame's pose in the reference's optical frame. For whoever relocalizes a
     * frame against an earlier one (a node decider after VO was lost). */
    struct Alignment {
        bool success{false};
        VoFailure failure{VoFailure::None};
        RigidEstimate estimate;
        std::size_t matches{0}, inliers{0};
        VoTiming timing;
    };
    Alignment align(const FrameFeatures& reference, const FrameFeatures& current,
                    std::uint64_t seed) const;
    /** Forgets the reference: the next frame starts afresh. */
    void reset();

    VoState state() const { return state_; }
    const VoTotals& totals() const { return totals_; }
    const Params& params() const { return params_; }

  private:
    /** The frame's depth points, sampled once when first asked for. */
    using DepthCloudSource = std::function<DepthCloud&()>;

    /** VO's frame pipeline: a start, or the features matched, the depth where they fail (or
     * joined with them), the gyro joined, the keyframe decided. */
    VoResult processFrame(PreparedFrame& prepared, const MotionPrior* prior,
                          const RotationPrior* rotation);
    /** Starts (again) from this frame if it holds enough features, or depth to align by
     * (`depthStart`): false if neither. */
    bool startFrom(FrameFeatures& features, double timestamp, const DepthCloudSource& cloud);
    /** The frame (its features, its depth points into the depth model) as the new reference,
     * at `T_ref_new` in the old one. */
    void becomeReference(FrameFeatures& features, double timestamp,
                         const Eigen::Isometry3d& T_ref_new, bool pinned,
                         const DepthCloudSource& cloud);
    /** The features matched with the reference's, guided by the prior where one is given and
     * it holds, else by brute force; the time taken into `r`. */
    Alignment matchFeatures(const FrameFeatures& current, const RgbdFrame& frame,
                            const MotionPrior* prior, std::uint64_t seed, VoResult& r);
    /** Where the features failed: `est` from the depth alone, if it aligned plausibly. */
    bool alignByDepthAlone(const DepthCloud& points, double timestamp, const MotionPrior* prior,
                           const RotationPrior* rotation, RigidEstimate& est, VoResult& r);
    /** Where the features aligned: the depth solved with them, `est` replaced if plausible. */
    void joinDepth(const DepthCloud& points, double timestamp, RigidEstimate& est, VoResult& r);
    /** The gyro's rotation joined with `est` (`gyroWithFeatures`), where it applies. */
    void joinGyro(const RotationPrior* rotation, double timestamp, RigidEstimate& est,
                  VoResult& r) const;
    /** Depth alignment where the features failed, started from the prior, else the rotation
     * (or constant turn rate) and the carrier's fading velocity. */
    DepthAlignment alignDepth(const DepthCloud& cloud, double timestamp, const MotionPrior* prior,
                              const RotationPrior* rotation) const;
    /** The frame's pose in the reference by constant velocity since the last tracked frame
     * (its rotation starts a depth alignment). */
    Eigen::Isometry3d constantVelocity(double timestamp) const;
    /** Whether a tracked frame, measured at `measured` from the reference, replaces it
     * (`keyframeDistance`, `keyframeAngle`, `keyframeBy`). */
    bool isKeyframe(const Eigen::Isometry3d& measured, const MotionPrior* prior,
                    const RotationPrior* rotation) const;
    /** Remembers a tracked frame's pose in the reference, for constant velocity; and the
     * carrier's velocity - measured since the reference where the features aligned, faded by
     * `velocitySeconds` where only the depth did. */
    void trackedAt(const Eigen::Isometry3d& T_ref_cur, double timestamp, bool becameReference,
                   bool measured, double velocitySeconds);
    /** RANSAC on given matches (the second half of `align`). */
    Alignment alignMatches(const FrameFeatures& reference, const FrameFeatures& current,
                           const std::vector<cv::DMatch>& matches, std::uint64_t seed) const;
    /** None, or why the motion is implausible: beyond the reference bounds, or faster than the
     * carrier since the last tracked frame (at `timestamp`). */
    VoFailure plausibility(const RigidEstimate& estimate, double timestamp) const;
    /** `est` becomes T with that covariance if that is plausible (true), else stays. */
    bool replaceIfPlausible(RigidEstimate& est, const Eigen::Isometry3d& T,
                            const Eigen::Matrix<double, 6, 6>& covariance, double timestamp) const;

    Params params_;
    DescriptorMatcher matcher_;
    GuidedMatcher guided_;
    RigidRansac ransac_;
    PointToPlaneIcp icp_;
    DepthModel depth_model_;
    /** The last tracked frame: its pose in the reference and time, and the step before it. */
    Eigen::Isometry3d last_in_ref_{Eigen::Isometry3d::Identity()};
    double last_time_{0};
    Eigen::Isometry3d last_step_{Eigen::Isometry3d::Identity()};
    double last_step_dt_{0};
    /** The carrier's velocity at the last tracked frame, in the reference's frame [m/s]. */
    Eigen::Vector3d velocity_{Eigen::Vector3d::Zero()};
    std::optional<FrameFeatures> reference_;
    double reference_time_{0};
    int failures_{0};
    VoState state_{VoState::Initializing};
    std::uint64_t frame_count_{0};
    VoTotals totals_;
};

}  // namespace lodestone::vision
