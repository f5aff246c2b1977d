#include <lodestone/sim/SimRgbdCamera.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

namespace lodestone::sim {

SimRgbdCamera::SimRgbdCamera(const World& world, const MotionPlan& plan, const CameraSpec& spec,
                             double startTime, Random rng, const HandheldMotion* handheld)
    : plan_(plan),
      handheld_(handheld),
      spec_(spec),
      start_time_(startTime),
      rng_(rng),
      clock_(spec.rate),
      renderer_(world, spec, rng.fork(7).nextU64()) {}

std::int64_t SimRgbdCamera::nextTimeNs() const { return clock_.nextWithin(plan_.duration()); }

mrpt::obs::CObservation::Ptr SimRgbdCamera::produce() {
    const std::int64_t tNs = clock_.now();
    ++clock_.k;
    const auto& m = spec_.pose;
    cv::Mat3b rgb;
    cv::Mat_<uint16_t> depth;
    if (handheld_) {
        renderer_.render(handheld_->poseAt(tNs * 1e-9), rng_, rgb, depth);
    } else {
        const SensorWorldPose s = sensorInWorld(plan_.poseAt(tNs * 1e-9), m.x, m.y, m.z, m.yaw);
        renderer_.render(s.position, s.yaw, rng_, rgb, depth);
    }

    auto obs = mrpt::obs::CObservation3DRangeScan::Create();
    obs->timestamp = simTimestamp(start_time_, tNs);
    obs->sensorLabel = spec_.label;
    obs->sensorPose = handheld_ ? mrpt::poses::CPose3D() : mrpt::poses::CPose3D(m.x, m.y, m.z, m.yaw, 0, 0);
    auto& cam = obs->cameraParams;
    cam.ncols = static_cast<uint32_t>(spec_.width);
    cam.nrows = static_cast<uint32_t>(spec_.height);
    cam.fx(spec_.fx);
    cam.fy(spec_.fy);
    cam.cx(spec_.cx);
    cam.cy(spec_.cy);
    obs->cameraParamsIntensity = cam;
    obs->maxRange = static_cast<float>(spec_.maxRange);
    obs->range_is_depth = true;
    obs->rangeUnits = 0.001f;
    obs->hasRangeImage = true;
    obs->rangeImage_setSize(spec_.height, spec_.width);
    for (int r = 0; r < spec_.height; ++r) {
        for (int c = 0; c < spec_.width; ++c) obs->rangeImage(r, c) = depth(r, c);
    }
    obs->hasIntensityImage = true;
    obs->intensityImageChannel = mrpt::obs::CObservation3DRangeScan::CH_VISIBLE;
    obs->intensityImage = mrpt::img::CImage(rgb, mrpt::img::DEEP_COPY);
    return obs;
}

}  // namespace lodestone::sim
