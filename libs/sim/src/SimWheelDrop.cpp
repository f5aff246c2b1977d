#include <lodestone/obs/CObservationWheelDrop.h>
#include <lodestone/sim/SimWheelDrop.h>

#include <cmath>
#include <limits>

namespace lodestone::sim {

SimWheelDrop::SimWheelDrop(const MotionPlan& plan, const std::string& label, double startTime)
    : label_(label), start_time_(startTime) {
    for (const auto& s : plan.segments()) {
        if (s.kind != MotionSegment::Kind::Carry) continue;
        events_.emplace_back(static_cast<std::int64_t>(std::llround(s.t0 * 1e9)), true);
        events_.emplace_back(static_cast<std::int64_t>(std::llround(s.t1 * 1e9)), false);
    }
}

std::int64_t SimWheelDrop::nextTimeNs() const {
    return next_ < events_.size() ? events_[next_].first : std::numeric_limits<std::int64_t>::max();
}

mrpt::obs::CObservation::Ptr SimWheelDrop::produce() {
    const auto [tNs, lifted] = events_.at(next_++);
    auto obs = lodestone::obs::CObservationWheelDrop::Create();
    obs->timestamp = simTimestamp(start_time_, tNs);
    obs->sensorLabel = label_;
    obs->leftDropped = lifted;
    obs->rightDropped = lifted;
    return obs;
}

}  // namespace lodestone::sim
