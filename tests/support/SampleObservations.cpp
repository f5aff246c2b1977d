#include "SampleObservations.h"

#include <mrpt/io/CMemoryStream.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt/system/datetime.h>

#include <algorithm>
#include <cmath>

namespace lodestone::test {

using mrpt::obs::CObservation;

namespace {
mrpt::Clock::time_point stamp(double t) { return mrpt::Clock::fromDouble(t); }

// Robot on a circle of radius 2 m at 0.3 m/s.
constexpr double kRadius = 2.0, kSpeed = 0.3;
struct Pose2 {
    double x, y, yaw;
};
Pose2 drivePose(double s) {  // s: seconds since start
    const double a = kSpeed * s / kRadius;
    return {kRadius * std::sin(a), kRadius * (1 - std::cos(a)), a};
}

// Earth field plus one dipole-like bump near (1, 1), world frame [uT].
mrpt::math::TVector3D worldField(double x, double y) {
    const double d2 = (x - 1) * (x - 1) + (y - 1) * (y - 1);
    const double bump = 25.0 * std::exp(-d2 / 0.5);
    return {22.0 + bump * (x - 1), 1.5 + bump * (y - 1), -44.0 + bump};
}
}  // namespace

lodestone::obs::CObservationMagnetometer::Ptr makeMagnetometer(double t, const std::string& label,
                                                               double seedValue) {
    auto m = lodestone::obs::CObservationMagnetometer::Create();
    m->timestamp = stamp(t);
    m->sensorLabel = label;
    m->sensorPose = mrpt::poses::CPose3D(0.1, seedValue * 0.01, 0.3, 0, 0, 0);
    m->field = {20.0 + seedValue, -3.5 + 0.5 * seedValue, -44.25 - seedValue};
    m->noiseStd = {0.2, 0.2, 0.3};
    if (static_cast<int>(seedValue) % 2 == 0) m->temperature = 21.5 + seedValue;
    m->calibrated = true;
    return m;
}

mrpt::obs::CObservationIMU::Ptr makeImu(double t, const std::string& label, double seedValue) {
    auto imu = mrpt::obs::CObservationIMU::Create();
    imu->timestamp = stamp(t);
    imu->sensorLabel = label;
    imu->sensorPose = mrpt::poses::CPose3D(0, 0, 0.2, 0, 0, 0);
    imu->set(mrpt::obs::IMU_X_ACC, 0.01 * seedValue);
    imu->set(mrpt::obs::IMU_Y_ACC, -0.02 * seedValue);
    imu->set(mrpt::obs::IMU_Z_ACC, 9.81);
    imu->set(mrpt::obs::IMU_WZ, 0.15);
    imu->set(mrpt::obs::IMU_MAG_X, 0.21 + 0.001 * seedValue);
    imu->set(mrpt::obs::IMU_MAG_Y, 0.02);
    imu->set(mrpt::obs::IMU_MAG_Z, -0.44);
    return imu;
}

mrpt::obs::CObservationOdometry::Ptr makeOdometry(double t, double seedValue) {
    auto o = mrpt::obs::CObservationOdometry::Create();
    o->timestamp = stamp(t);
    o->sensorLabel = "WHEELS";
    o->odometry = mrpt::poses::CPose2D(0.1 * seedValue, 0.05 * seedValue, 0.01 * seedValue);
    o->hasEncodersInfo = true;
    o->encoderLeftTicks = static_cast<int32_t>(100 * seedValue);
    o->encoderRightTicks = static_cast<int32_t>(104 * seedValue);
    o->hasVelocities = true;
    o->velocityLocal = mrpt::math::TTwist2D(kSpeed, 0, kSpeed / kRadius);
    return o;
}

mrpt::obs::CObservation3DRangeScan::Ptr makeRangeScan(double t, int width, int height,
                                                      double seedValue) {
    auto s = mrpt::obs::CObservation3DRangeScan::Create();
    s->timestamp = stamp(t);
    s->sensorLabel = "RGBD";
    s->sensorPose = mrpt::poses::CPose3D(0.15, 0, 0.45, 0, 0, 0);
    s->cameraParams.ncols = width;
    s->cameraParams.nrows = height;
    s->cameraParams.fx(width * 0.89);
    s->cameraParams.fy(width * 0.89);
    s->cameraParams.cx(width / 2.0);
    s->cameraParams.cy(height / 2.0);
    s->cameraParamsIntensity = s->cameraParams;
    s->hasRangeImage = true;
    s->range_is_depth = true;
    s->rangeUnits = 0.001f;
    s->rangeImage.resize(height, width);
    s->hasIntensityImage = true;
    s->intensityImage.resize(width, height, mrpt::img::CH_RGB);
    const int shift = static_cast<int>(seedValue * 3);
    for (int r = 0; r < height; ++r) {
        for (int c = 0; c < width; ++c) {
            // A slanted wall 1.5-2.5 m away; the top-left corner is invalid (0), as in Kinect.
            const bool invalid = r < 3 && c < 3;
            s->rangeImage(r, c) =
                invalid ? 0 : static_cast<uint16_t>(1500 + 1000 * c / std::max(1, width - 1));
            const bool dark = (((c + shift) / 8) + (r / 8)) % 2 == 0;
            auto* px = s->intensityImage.ptr<uint8_t>(c, r);
            px[0] = dark ? 40 : 200;
            px[1] = static_cast<uint8_t>((c * 255) / std::max(1, width));
            px[2] = static_cast<uint8_t>((r * 255) / std::max(1, height));
        }
    }
    return s;
}

std::vector<CObservation::Ptr> makeSampleDrive(const SampleDriveOptions& opt) {
    struct Stamped {
        double t;
        int order;
        CObservation::Ptr obs;
    };
    std::vector<Stamped> all;
    const auto addSeries = [&](double rate, int order, auto make) {
        const int n = static_cast<int>(std::floor(opt.duration * rate)) + 1;
        for (int i = 0; i < n; ++i) {
            const double s = i / rate;
            all.push_back({s, order, make(opt.t0 + s, s, i)});
        }
    };
    const double ticksPerMetre = 2000.0, wheelBase = 0.23;
    addSeries(opt.odometryRate, 0, [&](double t, double s, int) -> CObservation::Ptr {
        const Pose2 p = drivePose(s);
        auto o = makeOdometry(t, 0);
        o->odometry = mrpt::poses::CPose2D(p.x, p.y, p.yaw);
        const double dist = kSpeed * s, dyaw = p.yaw;
        o->encoderLeftTicks = static_cast<int32_t>((dist - dyaw * wheelBase / 2) * ticksPerMetre);
        o->encoderRightTicks = static_cast<int32_t>((dist + dyaw * wheelBase / 2) * ticksPerMetre);
        return o;
    });
    for (int k = 0; k < 2; ++k) {
        const std::string label = k == 0 ? "MAG_LEFT" : "MAG_RIGHT";
        const double side = k == 0 ? 0.12 : -0.12;
        addSeries(opt.magnetometerRate, 1 + k, [&, label, side](double t, double s, int i) {
            const Pose2 p = drivePose(s);
            const double sx = p.x - side * std::sin(p.yaw), sy = p.y + side * std::cos(p.yaw);
            const auto w = worldField(sx, sy);
            auto m = makeMagnetometer(t, label, 0);
            m->sensorPose = mrpt::poses::CPose3D(0, side, 0.3, 0, 0, 0);
            // World -> sensor frame: rotate by -yaw about z; small deterministic "noise".
            const double c = std::cos(p.yaw), sn = std::sin(p.yaw);
            const double wiggle = 0.2 * std::sin(37.0 * i + k);
            m->field = {c * w.x + sn * w.y + wiggle, -sn * w.x + c * w.y - wiggle, w.z};
            m->temperature = 24.0 + 0.01 * s;
            return m;
        });
    }
    addSeries(opt.imuRate, 3, [&](double t, double s, int) {
        auto imu = makeImu(t, "IMU", s);
        return imu;
    });
    addSeries(opt.cameraRate, 4, [&](double t, double s, int) {
        return makeRangeScan(t, opt.cameraWidth, opt.cameraHeight, s);
    });
    std::stable_sort(all.begin(), all.end(), [](const Stamped& a, const Stamped& b) {
        return a.t != b.t ? a.t < b.t : a.order < b.order;
    });
    std::vector<CObservation::Ptr> out;
    out.reserve(all.size());
    for (auto& s : all) out.push_back(std::move(s.obs));
    return out;
}

bool serializeEqual(const mrpt::serialization::CSerializable& a,
                    const mrpt::serialization::CSerializable& b) {
    mrpt::io::CMemoryStream ma, mb;
    auto aa = mrpt::serialization::archiveFrom(ma);
    auto ab = mrpt::serialization::archiveFrom(mb);
    aa << a;
    ab << b;
    if (ma.getTotalBytesCount() != mb.getTotalBytesCount()) return false;
    return std::equal(static_cast<const uint8_t*>(ma.getRawBufferData()),
                      static_cast<const uint8_t*>(ma.getRawBufferData()) + ma.getTotalBytesCount(),
                      static_cast<const uint8_t*>(mb.getRawBufferData()));
}

}  // namespace lodestone::test
