#pragma once

#include <lodestone/sim/MotionPlan.h>
#include <lodestone/sim/SurfaceTexture.h>

#include <Eigen/Core>
#include <cstdint>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace lodestone::sim {

/** A polyline of walls sharing one surface style, as written in the INI. */
struct WallSpec {
    std::string name;  ///< INI key, for messages
    SurfaceSpec surface;
    std::vector<Eigen::Vector2d> points;
};

/** A sensor's pose on the robot: position [m] and yaw [rad] (sensors are mounted level). */
struct MountPose {
    double x{0}, y{0}, z{0}, yaw{0};
};

struct CameraSpec {
    /** Largest image side the simulator renders [px] (a 100000x100000 typo is 30 GB). */
    static constexpr int kMaxSide = 4096;
    bool enabled{true};
    std::string label{"RGBD"};
    double rate{30};                                    ///< [Hz]
    int width{640}, height{480};                        ///< [px]
    double fx{570.3}, fy{570.3}, cx{319.5}, cy{239.5};  ///< [px]
    MountPose pose{0.10, 0.0, 0.45, 0.0};
    double minRange{0.5}, maxRange{5.0};  ///< valid depth [m]
    double depthNoise{1.425e-3};          ///< sigma(z) = depthNoise * z^2 [1/m]
    double disparityStep{2.85e-3};        ///< depth steps of disparityStep * z^2 [1/m]; 0: none
    double maxIncidence{1.309};           ///< beyond this angle to the normal: no depth [rad]
    double rgbNoise{2.0};                 ///< per-channel intensity noise std [0..255]
    bool externalImages{true};  ///< when written to a rawlog: images beside it, not inside
    /** Colour files beside the rawlog: "png" (lossless) or "jpg" (`jpegQuality`, 1..100). */
    std::string imageFormat{"png"};
    int jpegQuality{90};

    /** Changes the image size, scaling the intrinsics with it (principal point centred). */
    void resize(int newWidth, int newHeight);
    /** Applies "WIDTHxHEIGHT@RATE" (e.g. "320x240@15"); false, leaving the camera as it was,
     * when the text is not that (or below 16x16, or a rate <= 0). */
    bool override(const std::string& widthHeightRate);
    /** Applies "png", "jpg" or "jpg:QUALITY"; false, leaving it as it was, otherwise. */
    bool setImageFormat(const std::string& text);
};

struct MagnetometerSpec {
    std::string label;
    double rate{100};  ///< [Hz]
    MountPose pose;
    double noiseStd{0.3};           ///< per-axis white noise [uT]
    Eigen::Vector3d bias{0, 0, 0};  ///< constant, sensor frame [uT]
};

/** An IMU's 3-axis rate gyro and accelerometer, on the robot at `pose` or rigid with a
 * hand-held camera. */
struct GyroSpec {
    std::string label{"IMU"};
    double rate{100};  ///< [Hz]
    MountPose pose;    ///< on the robot (a hand-held gyro is the camera's frame)
    /** Per-axis white noise of each sample [rad/s]: 0.07 deg/s, a MEMS IMU's noise density
     * (0.007 deg/s/sqrt(Hz), Xsens MTi class) at 100 Hz. */
    double noiseStd{0.07 * M_PI / 180};
    /** Each axis' constant bias, drawn per run from N(0, biasSigma) [rad/s]: 0.1 deg/s, an
     * uncalibrated MEMS gyro's turn-on bias. */
    double biasSigma{0.1 * M_PI / 180};
    /** The accelerometer's per-axis white noise of each sample [m/s^2]: 0.01, a MEMS IMU's
     * noise density (100 ug/sqrt(Hz), Xsens MTi-3 class) at 100 Hz. */
    double accelNoiseStd{0.01};
    /** Each axis' constant accelerometer bias, drawn per run from N(0, accelBiasSigma)
     * [m/s^2]: 0.02 (2 mg), a factory-calibrated MEMS accelerometer's residual offset. */
    double accelBiasSigma{0.02};
};

struct EncoderSpec {
    std::string label{"WHEELS"};
    double rate{50};                         ///< [Hz]
    double ticksPerRev{2578.33};             ///< Kobuki: 52 ticks x 49.58 gear ratio
    double slipStd{0.01};                    ///< relative noise on each wheel increment
    double leftScale{1.0}, rightScale{1.0};  ///< systematic wheel radius errors (1: none)
    std::string wheelDropLabel{"WHEEL_DROP"};
};

struct FieldSpec {
    double earthMagnitude{50};  ///< [uT]
    double inclination{1.15};   ///< [rad] (66 deg, mid-latitude Europe / Korea)
    double declination{0.0};    ///< [rad] from world +x
    double wallSpacing{0.5};    ///< rebar dipoles along walls, one per spacing [m]; 0: none
    Eigen::Vector2d wallMoment{1.0, 6.0};    ///< moment range [A m^2]
    double floorDensity{0.5};                ///< floor dipoles per m^2
    Eigen::Vector2d floorDepth{0.05, 0.4};   ///< below the floor [m]
    Eigen::Vector2d floorMoment{2.0, 12.0};  ///< [A m^2]
    struct Line {
        Eigen::Vector3d a, b, momentPerMetre;
        double spacing;
    };
    std::vector<Line> lines;                                           ///< explicit beams
    std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> dipoles;  ///< explicit (pos, m)
};

/** How a camera carried by hand moves about its carrier's path. */
struct HandheldSpec {
    double height{1.35};   ///< [m] camera above the floor
    double bob{0.02};      ///< [m] vertical amplitude (walking)
    double sway{0.02};     ///< [m] sideways amplitude
    double shakeDeg{2.0};  ///< [deg] amplitude of each of yaw, pitch, roll
};

/** Everything a scenario INI says, validated. */
struct Scenario {
    std::string name, source;  ///< scenario name; the INI path (for messages)
    std::uint64_t seed{1};
    /** The building's own seed (wall textures, the magnetic field's anomalies); unset: drawn
     * from the run's seed, so every seed is another building. Set, runs of other seeds are
     * other sensor noise in one building - what a map saved by one run and used by the next
     * needs. */
    std::optional<std::uint64_t> worldSeed;
    double startTime{1.7e9};  ///< epoch of t = 0 [s]
    double wallHeight{2.6};   ///< walls reach the ceiling [m]
    double texturePixelsPerMetre{200};
    /** `texture_filter = area`: a camera pixel's colour is the texture averaged over the
     * pixel's footprint on the surface, as a sensor integrates light over its area. `point`
     * (the default, every figure so far): the texture sampled at the pixel's centre, which
     * aliases wherever a pixel covers more than a texel - features on the aliased pattern slide
     * over the surface, and the robot camera's VO steps come out 3.3 % short where area makes
     * them 1.8 %. Area is not the default yet: the fused odometry's remaining length bias then
     * reaches the map (docs/results/simulator.md). */
    bool areaFilteredTextures{false};
    SurfaceSpec floor, ceiling;
    double lampSpacing{2.5};  ///< ceiling lamps on a grid [m]
    std::vector<WallSpec> walls;
    MotionPlan::Params motion;
    double robotRadius{0.18};  ///< [m]
    EncoderSpec encoders;
    CameraSpec camera;
    std::vector<MagnetometerSpec> magnetometers;
    /** A gyro ([gyro] section, or lodestone-sim --gyro); none when unset. */
    std::optional<GyroSpec> gyro;
    FieldSpec field;
    std::vector<KidnapSpec> kidnaps;
    /** Only the RGB-D camera records (no encoders, wheel drop or magnetometers): a camera-only
     * recording, as a handheld sequence or an RGB-D dataset is (lodestone-sim --camera-only). */
    bool cameraOnly{false};
    /** The camera carried by hand along the path (sim::HandheldMotion): 6-DoF, shaking; implies
     * cameraOnly (lodestone-sim --handheld). */
    std::optional<HandheldSpec> handheld;

    /** Reads and validates an INI; throws config::ConfigError naming the file, section and key
     * (or waypoint / kidnap) at fault. */
    static Scenario load(const std::string& iniPath);
};

}  // namespace lodestone::sim
