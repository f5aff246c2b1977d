#include <lodestone/eval/FieldMapPlot.h>

#include <algorithm>
#include <cmath>

namespace lodestone::eval {

TrajectoryInterpolator::TrajectoryInterpolator(std::vector<io::TumPose> trajectory, double maxGap,
                                               double stillRadius)
    : poses_(std::move(trajectory)), max_gap_(maxGap), still_radius_(stillRadius) {
    std::stable_sort(poses_.begin(), poses_.end(),
                     [](const io::TumPose& a, const io::TumPose& b) { return a.timestamp < b.timestamp; });
}

bool TrajectoryInterpolator::bridges(const io::TumPose& a, const io::TumPose& b) const {
    return b.timestamp - a.timestamp <= max_gap_ || a.pose.distanceTo(b.pose) <= still_radius_;
}

std::vector<std::vector<cv::Point2d>> TrajectoryInterpolator::pieces() const {
    std::vector<std::vector<cv::Point2d>> out;
    for (std::size_t i = 0; i < poses_.size(); ++i) {
        if (i == 0 || !bridges(poses_[i - 1], poses_[i])) out.emplace_back();
        out.back().emplace_back(poses_[i].pose.x(), poses_[i].pose.y());
    }
    return out;
}

std::optional<mrpt::poses::CPose3D> TrajectoryInterpolator::at(double time) const {
    if (poses_.empty() || !std::isfinite(time)) return std::nullopt;
    const auto after = std::lower_bound(
        poses_.begin(), poses_.end(), time,
        [](const io::TumPose& p, double t) { return p.timestamp < t; });
    if (after == poses_.end()) return std::nullopt;
    if (after->timestamp == time) return after->pose;
    if (after == poses_.begin()) return std::nullopt;
    const auto& b = *after;
    const auto& a = *(after - 1);
    const double span = b.timestamp - a.timestamp;
    if (!bridges(a, b)) return std::nullopt;
    const double u = span > 0 ? (time - a.timestamp) / span : 0.0;
    // The motion from a to b, scaled by u on the manifold: a (+) exp(u log(a^-1 b)) would be
    // exact; between nodes centimetres apart a linear blend of translation and yaw/pitch/roll
    // deltas is the same to well under a cell.
    const mrpt::poses::CPose3D d = b.pose - a.pose;
    const auto wrap = [](double r) { return std::remainder(r, 2 * M_PI); };
    const mrpt::poses::CPose3D step(u * d.x(), u * d.y(), u * d.z(), u * wrap(d.yaw()),
                                    u * wrap(d.pitch()), u * wrap(d.roll()));
    return a.pose + step;
}

FieldMapBuilder::FieldMapBuilder(std::vector<io::TumPose> trajectory, double cellSize,
                                 double maxGap)
    : trajectory_(std::move(trajectory), maxGap), grid_(cellSize) {}

bool FieldMapBuilder::add(double time, const mrpt::math::TPoint3D& sensorOffset,
                          double magnitude, const std::string& label) {
    const auto robot = trajectory_.at(time);
    if (!robot || !std::isfinite(magnitude)) {
        ++unplaced_;
        return false;
    }
    const mrpt::math::TPoint3D at = robot->composePoint(sensorOffset);
    grid_.add(at.x, at.y, magnitude);
    labels_.insert(label);
    ++placed_;
    return true;
}

cv::Mat3b FieldMapBuilder::render(const std::string& title) const {
    std::string sensors;
    for (const auto& l : labels_) sensors += (sensors.empty() ? "" : ", ") + l;
    plot::PlaneMapStyle style;
    style.title = title + (sensors.empty() ? "" : " - " + sensors);
    style.unit = "|B| [uT]";
    return plot::renderPlaneMap(grid_, trajectory_.pieces(), style);
}

}  // namespace lodestone::eval
