#include <lodestone/odometry/CruiseVelocity.h>

#include <cmath>

namespace lodestone::odometry {

void CruiseVelocity::add(const Eigen::Vector3d& displacement, double seconds) {
    if (!(seconds_ > 0) || !(seconds > 0) || !displacement.allFinite()) return;
    // (displacement over time, not each step's velocity averaged: a frame's few millimetres
    // of VO error are a tenth of a metre per second, and cancel from one step to the next)
    const double keep = std::exp(-seconds / seconds_);
    moved_ = keep * moved_ + displacement;
    tracked_ = keep * tracked_ + seconds;
    mean_ = moved_ / tracked_;
}

}  // namespace lodestone::odometry
