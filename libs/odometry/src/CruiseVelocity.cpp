#include <lodestone/odometry/CruiseVelocity.h>

#include <algorithm>
#include <cmath>

namespace lodestone::odometry {

namespace {
/** The window's turn rates reach their mean plus this many sigma (normal, 99 %). */
constexpr double kRateReach = 2.576;
}  // namespace

void CruiseVelocity::add(const Eigen::Vector3d& displacement, double seconds, double turnRate) {
    if (!(seconds_ > 0) || !(seconds > 0) || !displacement.allFinite() || !std::isfinite(turnRate))
        return;
    // (displacement over time, not each step's velocity averaged: a frame's few millimetres
    // of VO error are a tenth of a metre per second, and cancel from one step to the next)
    const double keep = std::exp(-seconds / seconds_), w = std::abs(turnRate);
    time_ = keep * time_ + seconds;
    rate_ = keep * rate_ + seconds * w;
    rate2_ = keep * rate2_ + seconds * w * w;
    moved_ = keep * moved_ + displacement;
    moved_rate_ = keep * moved_rate_ + displacement * w;
}

double CruiseVelocity::rateSpread2() const {
    // (the rates' spread, with their own error: never narrower than that)
    const double meanRate = rate_ / time_;
    return std::max(0.0, rate2_ / time_ - meanRate * meanRate) + rate_sigma_ * rate_sigma_;
}

bool CruiseVelocity::knows(double turnRate) const {
    return time_ > 0 && std::abs(turnRate) <= rate_ / time_ + kRateReach * std::sqrt(rateSpread2());
}

Eigen::Vector3d CruiseVelocity::at(double turnRate) const {
    if (!knows(turnRate)) return Eigen::Vector3d::Zero();
    const double meanRate = rate_ / time_, spread2 = rateSpread2();
    const Eigen::Vector3d mean = moved_ / time_;
    const Eigen::Vector3d slope = (moved_rate_ / time_ - mean * meanRate) / spread2;
    return mean + slope * (std::abs(turnRate) - meanRate);
}

}  // namespace lodestone::odometry
