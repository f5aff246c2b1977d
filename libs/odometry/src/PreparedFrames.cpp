#include <lodestone/odometry/PreparedFrames.h>
#include <lodestone/odometry/RgbdObservationFrame.h>

#include <algorithm>

namespace lodestone::odometry {

PreparedFrames::PreparedFrames(Prepare prepare) : prepare_(std::move(prepare)) {}

void PreparedFrames::setCapacity(std::size_t frames) {
    std::lock_guard<std::mutex> lock(mutex_);
    capacity_ = frames;
}

void PreparedFrames::onlyCamera(const std::string& label) {
    std::lock_guard<std::mutex> lock(mutex_);
    camera_ = label;
}

void PreparedFrames::prepareAhead(const mrpt::obs::CObservation::Ptr& obs) {
    const auto* scan = dynamic_cast<const mrpt::obs::CObservation3DRangeScan*>(obs.get());
    if (!scan) return;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (capacity_ == 0 || (!camera_.empty() && scan->sensorLabel != camera_)) return;
    }
    vision::PreparedFrame prepared;
    try {
        prepared = prepare_(frameFromObservation(*scan));
    } catch (...) {
        return;  // (take() prepares it again, and meets the error where it always did)
    }
    std::lock_guard<std::mutex> lock(mutex_);
    ready_.emplace_back(obs, std::move(prepared));
    while (ready_.size() > capacity_) {
        ready_.pop_front();
        ++counts_.dropped;
    }
}

vision::PreparedFrame PreparedFrames::take(const mrpt::obs::CObservation3DRangeScan& obs) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        const auto it = std::find_if(ready_.begin(), ready_.end(),
                                     [&](const auto& r) { return r.first.get() == &obs; });
        if (it != ready_.end()) {
            vision::PreparedFrame prepared = std::move(it->second);
            ready_.erase(it);
            ++counts_.ahead;
            return prepared;
        }
        ++counts_.here;
    }
    return prepare_(frameFromObservation(obs));
}

PreparedFrames::Counts PreparedFrames::counts() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return counts_;
}

}  // namespace lodestone::odometry
