#include <lodestone/graphslam/erd/magnetic/MagneticPath.h>
#include <lodestone/magnetic/FieldFeatures.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace lodestone::graphslam {

void MagneticPath::addNode(TNodeID id, const Graph& graph, const NodeStore& nodes,
                           std::string& label, double saturation, const ReadingSink& sink) {
    addNode(
        id, graph, nodes, saturation,
        [&](const MagneticSample& m) {
            if (label.empty()) label = m.sensorLabel;
            return m.sensorLabel == label;
        },
        [&](const MagneticSample&, double s, const Eigen::Vector3d& b) { sink(s, b); });
}

void MagneticPath::addNode(TNodeID id, const Graph& graph, const NodeStore& nodes,
                           double saturation, const SensorFilter& take, const SensorSink& sink) {
    const NodeRecord& rec = nodes.at(id);
    double step = 0;
    double t0 = rec.timestamp;
    const Constraint* odometry = nullptr;
    if (id > 0) {
        const auto e = graph.edges.find({id - 1, id});
        // No travel across a kidnap: the edge there says nothing of the path.
        if (e != graph.edges.end() && rec.segment == segment.back()) {
            step = std::hypot(e->second.mean.x(), e->second.mean.y());
            odometry = &e->second;
        }
        t0 = nodes.at(id - 1).timestamp;
    }
    uncertainty.addNode(id, odometry, id > 0 ? graph.nodes.at(id - 1).yaw() : 0.0);
    const double s0 = travel.empty() ? 0.0 : travel.back();
    travel.push_back(s0 + step);
    segment.push_back(rec.segment);
    for (const auto& m : rec.magnetic) {
        if (!take(m)) {
            ++counts.otherSensors;
            continue;
        }
        ++counts.readings;
        const Eigen::Vector3d inSensor(m.field.x, m.field.y, m.field.z);
        if (!magnetic::usableReading(inSensor, saturation)) {
            ++counts.dropped;
            continue;
        }
        const double f = rec.timestamp > t0
                             ? std::clamp((m.timestamp - t0) / (rec.timestamp - t0), 0.0, 1.0)
                             : 1.0;
        sink(m, s0 + f * step, m.sensorPose.getRotationMatrix().asEigen() * inSensor);
    }
}

void MagneticPath::pinClosure(TNodeID query, double targetYaw, const Eigen::Matrix2d& positionCov,
                              double yawVariance) {
    const Eigen::Matrix2d R = Eigen::Rotation2Dd(targetYaw).toRotationMatrix();
    Eigen::Matrix3d pinned = Eigen::Matrix3d::Zero();
    pinned.topLeftCorner<2, 2>() = R * positionCov * R.transpose();
    pinned(2, 2) = yawVariance;
    uncertainty.pin(query, pinned);
}

void MagneticPath::pinKept(const std::vector<LoopClosure>& kept, const Graph& graph) {
    for (const auto& lc : kept) {
        // The edge's covariance is in the frame of its `from` node, whichever end is newer.
        const TNodeID newer = std::max(lc.from, lc.to);
        const auto from = graph.nodes.find(lc.from);
        if (newer >= travel.size() || from == graph.nodes.end()) continue;
        const Eigen::Matrix3d cov = closure::planarCovariance(lc.constraint);
        pinClosure(newer, from->second.yaw(), cov.topLeftCorner<2, 2>(), cov(2, 2));
    }
}

JsonObject& MagneticPath::describeCounts(JsonObject& stats) const {
    return stats.set("readings", counts.readings)
        .set("dropped_readings", counts.dropped)
        .set("other_sensor_readings", counts.otherSensors);
}

Eigen::Matrix2d alongAcross(const mrpt::poses::CPose3D& step, double along2, double across2) {
    const double len = std::hypot(step.x(), step.y());
    const Eigen::Vector2d u =
        len > 1e-6 ? Eigen::Vector2d(step.x() / len, step.y() / len) : Eigen::Vector2d(1, 0);
    const Eigen::Matrix2d P = u * u.transpose();
    return along2 * P + across2 * (Eigen::Matrix2d::Identity() - P);
}

JsonObject& describeQueryTimes(JsonObject& stats, const std::vector<double>& queryMs) {
    double total = 0, worst = 0;
    for (double ms : queryMs) {
        total += ms;
        worst = std::max(worst, ms);
    }
    return stats.set("query_ms_mean", queryMs.empty() ? 0.0 : total / double(queryMs.size()))
        .set("query_ms_max", worst);
}

}  // namespace lodestone::graphslam

namespace lodestone::graphslam {

Eigen::Vector3d MagneticPath::poseAt(const Graph& graph, TNodeID k, double at) const {
    const auto& b = graph.nodes.at(k);
    if (k == 0 || segment[k - 1] != segment[k] || travel[k] <= travel[k - 1])
        return {b.x(), b.y(), b.yaw()};
    const auto& a = graph.nodes.at(k - 1);
    const double f = std::clamp((at - travel[k - 1]) / (travel[k] - travel[k - 1]), 0.0, 1.0);
    return {a.x() + f * (b.x() - a.x()), a.y() + f * (b.y() - a.y()),
            a.yaw() + f * std::remainder(b.yaw() - a.yaw(), 2 * M_PI)};
}

std::vector<magnetic::FieldStretch> fieldFitStretches(const std::vector<double>& travel,
                                                      const std::vector<int>& segment,
                                                      const std::vector<Eigen::Vector3d>& field) {
    constexpr double kStep = 0.05;          // [m] a reading every
    constexpr std::size_t kStretch = 200;   // readings a stretch
    constexpr std::size_t kStretches = 40;  // at most, spread over the path
    std::vector<magnetic::FieldStretch> stretches;
    magnetic::FieldStretch current;
    std::vector<Eigen::Vector3d> rows;
    const auto flush = [&] {
        current.readings.resize(static_cast<Eigen::Index>(rows.size()), 3);
        for (std::size_t i = 0; i < rows.size(); ++i)
            current.readings.row(static_cast<Eigen::Index>(i)) = rows[i].transpose();
        if (current.travel.size() >= kStretch / 2) stretches.push_back(current);
        current = {};
        rows.clear();
    };
    double last = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < travel.size(); ++i) {
        if (i > 0 && segment[i] != segment[i - 1]) {
            flush();
            last = -std::numeric_limits<double>::infinity();
        }
        if (travel[i] - last < kStep) continue;
        last = travel[i];
        current.travel.push_back(travel[i]);
        rows.push_back(field[i]);
        if (rows.size() == kStretch) flush();
    }
    flush();
    if (stretches.size() <= kStretches) return stretches;
    std::vector<magnetic::FieldStretch> spread;
    for (std::size_t k = 0; k < kStretches; ++k)
        spread.push_back(stretches[k * stretches.size() / kStretches]);
    return spread;
}

mrpt::poses::CPosePDFGaussian closureFrom(const Eigen::Vector3d& from, const Eigen::Vector3d& here,
                                          const Eigen::Matrix3d& cov, double floor) {
    Eigen::Matrix3d J = Eigen::Matrix3d::Identity();
    J.topLeftCorner<2, 2>() = Eigen::Rotation2Dd(-from.z()).toRotationMatrix();
    Eigen::Matrix3d local = J * cov * J.transpose();
    local(0, 0) += floor * floor;
    local(1, 1) += floor * floor;
    return {mrpt::poses::CPose2D(here.x(), here.y(), here.z()) -
                mrpt::poses::CPose2D(from.x(), from.y(), from.z()),
            mrpt::math::CMatrixDouble33(local)};
}

}  // namespace lodestone::graphslam
