#include <lodestone/config/IniSection.h>
#include <lodestone/graphslam/nrd/KidnapDetector.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

namespace lodestone::graphslam::kidnap {

KidnapDetector::Params KidnapDetector::readParams(const mrpt::config::CConfigFileBase& ini) {
    Params p;
    config::IniSection s(ini, "kidnap_detection", config::sourceName(ini));
    p.motion = s.getBool("motion", p.motion);
    p.magnetic = s.getBool("magnetic", p.magnetic);
    const double chi2 = s.getDouble("chi2", 0);
    if (chi2 < 0) s.fail("chi2", "must be >= 0 (0: the 99.9 % quantile for 3 dof)");
    if (chi2 > 0) p.chi2 = chi2;
    p.floorSigmaXY = s.getDouble("floor_sigma_xy", p.floorSigmaXY);
    p.floorSigmaYaw = s.getDouble("floor_sigma_yaw_deg", p.floorSigmaYaw * 180 / M_PI) * M_PI / 180;
    p.floorRelative = s.getDouble("floor_relative", p.floorRelative);
    p.riseFloor = s.getDouble("rise_floor", p.riseFloor);
    p.persistence = s.getInt("persistence", p.persistence);
    p.settle = s.getDouble("settle", p.settle);
    p.magneticNoise = s.getDouble("magnetic_noise", p.magneticNoise);
    p.magneticGateSigma = s.getDouble("magnetic_gate_sigma", p.magneticGateSigma);
    p.magneticWindow = s.getDouble("magnetic_window", p.magneticWindow);
    p.window = s.getDouble("window", p.window);
    p.latency = s.getDouble("latency", p.latency);
    if (!(p.floorSigmaXY > 0) || !(p.floorSigmaYaw > 0))
        s.fail("floor_sigma_xy", "floors must be > 0");
    if (!(p.floorRelative >= 0)) s.fail("floor_relative", "must be >= 0");
    if (!(p.riseFloor > 0)) s.fail("rise_floor", "must be > 0");
    if (p.persistence < 1) s.fail("persistence", "must be >= 1");
    if (!(p.settle >= 0)) s.fail("settle", "must be >= 0");
    if (!(p.magneticNoise > 0)) s.fail("magnetic_noise", "must be > 0");
    if (!(p.magneticGateSigma > 0)) s.fail("magnetic_gate_sigma", "must be > 0");
    if (!(p.magneticWindow > 0)) s.fail("magnetic_window", "must be > 0");
    if (!(p.window > 0)) s.fail("window", "must be > 0");
    if (!(p.latency >= 2 * p.magneticWindow)) s.fail("latency", "must be >= 2 x magnetic_window");
    s.finish();
    return p;
}

std::optional<KidnapDetector::Event> KidnapDetector::lift(double t, const char* by) {
    lifted_ = true;
    inconsistent_ = 0;
    driving_since_.reset();
    field_.clear();
    ++stats_.lifts;
    const std::string b = by;
    if (b == "motion") ++stats_.byMotion;
    if (b == "rise") ++stats_.byRise;
    if (b == "magnetic") ++stats_.byMagnetic;
    return Event{true, t, b};
}

std::optional<KidnapDetector::Event> KidnapDetector::onFrame(
    const odometry::FusedOdometry::Estimate& e) {
    const double t = e.timestamp;
    const auto& step = e.wheel.mean;
    const bool still = std::hypot(step.x(), step.y()) < params_.stillStep &&
                       std::abs(step.phi()) < 10 * params_.stillStep;
    // Two tracks side by side: the encoders alone, and VO chained from its reference frames
    // (following the encoders where VO has no answer, so silence never looks like motion).
    FrameState now = last_;
    now.wheel = last_.wheel + step;
    now.wheelPositionVar += e.wheel.cov(0, 0) + e.wheel.cov(1, 1);
    now.wheelYawVar += e.wheel.cov(2, 2);
    const auto ref = frames_.find(e.visual.referenceTimestamp);
    const bool vo = params_.motion && e.visualSinceReference && ref != frames_.end();
    if (vo) {
        const auto& v = *e.visualSinceReference;
        now.visual = ref->second.visual + v.mean;
        now.visualPositionVar = ref->second.visualPositionVar + v.cov(0, 0) + v.cov(1, 1);
        now.visualYawVar = ref->second.visualYawVar + v.cov(2, 2);
        now.height = ref->second.height + e.visualRise;
        now.heightVar = ref->second.heightVar + e.visualRiseVariance;
    } else {
        now.visual = last_.visual + step;
    }
    last_ = now;
    frames_[t] = now;
    while (!frames_.empty() && frames_.begin()->first < t - 10.0) frames_.erase(frames_.begin());
    if (still) {
        if (!still_since_) {
            still_since_ = last_frame_time_ >= 0 ? last_frame_time_ : t;
            field_.clear();
        }
        driving_since_.reset();
    } else {
        still_since_.reset();
        field_.clear();
        if (!driving_since_) driving_since_ = t;
    }
    last_frame_time_ = t;

    // Since `from` (the frame at or before it): did the camera move as the wheels did, and
    // stay down? Empty when VO has no answer now.
    bool rose = false;
    const auto disagreeSince = [&](double from) -> std::optional<bool> {
        auto then = frames_.upper_bound(from);
        if (!vo || then == frames_.begin()) return std::nullopt;
        --then;
        const FrameState& a = then->second;
        const mrpt::poses::CPose2D w = now.wheel - a.wheel, v = now.visual - a.visual;
        // Both odometries err in proportion to the motion too (slip, scale, VO's own scale
        // and rotation errors at speed): a relative floor on top of the absolute one.
        const double k = params_.floorRelative;
        const auto floorVar = [&](const mrpt::poses::CPose2D& m) {
            const double travel = std::hypot(m.x(), m.y()), turn = std::abs(m.phi());
            return Eigen::Vector3d(
                params_.floorSigmaXY * params_.floorSigmaXY + k * k * travel * travel,
                params_.floorSigmaXY * params_.floorSigmaXY + k * k * travel * travel,
                params_.floorSigmaYaw * params_.floorSigmaYaw + k * k * turn * turn);
        };
        const auto chi2Of = [](const mrpt::poses::CPose2D& m, const Eigen::Vector3d& var) {
            const Eigen::Vector3d r(m.x(), m.y(), std::remainder(m.phi(), 2 * M_PI));
            return (r.array().square() / var.array()).sum();
        };
        const double wpv = (now.wheelPositionVar - a.wheelPositionVar) / 2;
        const double vpv = (now.visualPositionVar - a.visualPositionVar) / 2;
        const Eigen::Vector3d wVar =
            floorVar(w) + Eigen::Vector3d(wpv, wpv, now.wheelYawVar - a.wheelYawVar);
        const Eigen::Vector3d vVar =
            floorVar(v) + Eigen::Vector3d(vpv, vpv, now.visualYawVar - a.visualYawVar);
        // Carried: the camera moved, the wheels did not; wheels in the air: the reverse. (Both
        // moving but differently is a VO error, not a kidnap: VO slides sideways now and then.)
        const bool wheelsMoved = chi2Of(w, wVar) > params_.chi2;
        const bool cameraMoved = chi2Of(v, vVar) > params_.chi2;
        const bool differ = chi2Of(v - w, wVar + vVar) > params_.chi2;
        const bool carried = !wheelsMoved && cameraMoved, inTheAir = wheelsMoved && !cameraMoved;
        rose = still && std::abs(now.height - a.height) >
                            params_.riseFloor +
                                3 * std::sqrt(std::max(0.0, now.heightVar - a.heightVar));
        return (differ && (carried || inTheAir)) || rose;
    };
    if (!lifted_) {
        const auto disagree = disagreeSince(t - params_.window);
        if (!disagree) return std::nullopt;  // VO has nothing to say: keep the count
        if (!*disagree) {
            inconsistent_ = 0;
            return std::nullopt;
        }
        // The disagreement built up over the window: the lift is at most that far back.
        if (inconsistent_++ == 0) first_inconsistent_ = t;
        if (inconsistent_ < params_.persistence) return std::nullopt;
        // The disagreement took a while to pass the gate: a carried robot's wheels stopped
        // at the lift, so that is when it was, if it is recent enough to be this lift.
        const bool wheelsStopped =
            still_since_ && *still_since_ >= first_inconsistent_ - params_.window;
        return lift(wheelsStopped ? *still_since_ : first_inconsistent_, rose ? "rise" : "motion");
    }
    // Lifted: put down once the wheels drive again, VO (when it answers) agreeing with them
    // since they started.
    if (driving_since_) {
        const auto disagree = disagreeSince(*driving_since_);
        if (disagree && *disagree) driving_since_ = t;
    }
    if (driving_since_ && t - *driving_since_ >= params_.settle) {
        lifted_ = false;
        inconsistent_ = 0;
        ++stats_.putDowns;
        return Event{false, *driving_since_, "wheels"};
    }
    return std::nullopt;
}

std::optional<KidnapDetector::Event> KidnapDetector::onMagnetic(double t, double magnitude) {
    if (!params_.magnetic || lifted_ || !still_since_ || t < *still_since_ ||
        !std::isfinite(magnitude))
        return std::nullopt;
    // The first window after the wheels stopped against the latest one.
    field_.emplace_back(t, magnitude);
    const double w = params_.magneticWindow;
    if (t - *still_since_ < 2 * w) return std::nullopt;
    // Bounded: the first window and the latest one are all that is kept.
    const auto middle = std::find_if(field_.begin(), field_.end(),
                                     [&](const auto& f) { return f.first > *still_since_ + w; });
    field_.erase(middle, std::find_if(middle, field_.end(),
                                      [&](const auto& f) { return f.first >= t - w; }));
    double firstSum = 0, lastSum = 0;
    std::size_t firstN = 0, lastN = 0;
    for (const auto& [ti, m] : field_) {
        if (ti <= *still_since_ + w) {
            firstSum += m;
            ++firstN;
        }
        if (ti >= t - w) {
            lastSum += m;
            ++lastN;
        }
    }
    if (firstN == 0 || lastN == 0) return std::nullopt;
    const double sigma =
        params_.magneticNoise * std::sqrt(1.0 / double(firstN) + 1.0 / double(lastN));
    if (std::abs(lastSum / double(lastN) - firstSum / double(firstN)) <=
        params_.magneticGateSigma * sigma)
        return std::nullopt;
    return lift(t - w, "magnetic");
}

}  // namespace lodestone::graphslam::kidnap
