#pragma once
// Scripted walks through a 2-D field for the magnetic loop closers' tests: the field (the
// earth's plus anomalies scattered over the floor), a robot walking a polyline with its
// magnetometers, and what a scripted run replays - odometry steps, node records, the truth.
#include <lodestone/graphslam/NodeStore.h>
#include <lodestone/graphslam/PoseGraph.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPosePDFGaussian.h>

#include <Eigen/Core>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "ScriptedDeciders.h"

namespace lodestone::test {

/** The earth's field plus anomalies scattered over the floor (three per square metre,
 * 0.2-0.4 m wide, +-6 uT per component): a metre to the side the field is another. */
class FloorField {
  public:
    explicit FloorField(unsigned seed, double amplitude = 6) {
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> x(-6, 26), y(-2, 7), a(-amplitude, amplitude),
            w(0.2, 0.4);
        for (int k = 0; k < 3 * 32 * 9; ++k)
            bumps_.push_back({{x(rng), y(rng)}, {a(rng), a(rng), a(rng)}, w(rng)});
    }
    /** What a magnetometer at `p` facing `yaw` reads, in the levelled robot frame. */
    mrpt::math::TVector3D reading(const Eigen::Vector2d& p, double yaw) const {
        Eigen::Vector3d b(20, 0, -40);
        for (const auto& bump : bumps_) {
            const double d2 = (p - bump.at).squaredNorm();
            b += bump.amplitude * std::exp(-0.5 * d2 / (bump.width * bump.width));
        }
        const double c = std::cos(yaw), s = std::sin(yaw);
        return {c * b.x() + s * b.y(), -s * b.x() + c * b.y(), b.z()};
    }

  private:
    struct Bump {
        Eigen::Vector2d at;
        Eigen::Vector3d amplitude;
        double width;
    };
    std::vector<Bump> bumps_;
};

/** A magnetometer on the robot: its label and how far left of the centre line it sits. */
struct Mount {
    std::string label;
    double left{0};
};

/** A walk's script: the truth per node, the odometry steps (exact, claiming a good
 * odometry's noise; "anywhere" across a kidnap) and the node records with the readings. */
struct FloorWalkScript {
    std::vector<mrpt::poses::CPose2D> truth;
    std::vector<ScriptedNRD::Step> steps;
    std::vector<graphslam::NodeRecord> records;
};

/** Walks the polyline `corners` at 0.1 m per node, ten readings per node, odometry exact but
 * claiming the noise of a good one; turns on the spot at each corner. Leg `carried` (if any)
 * is a kidnap: the robot is put down at its end, facing along the next leg, in a new segment,
 * the odometry edge across it "anywhere". */
inline FloorWalkScript floorWalkScript(const std::vector<Eigen::Vector2d>& corners,
                                       const FloorField& field,
                                       const std::vector<Mount>& mounts = {{"MAG", 0}},
                                       int carried = -1, double readingNoise = 0) {
    FloorWalkScript w;
    std::mt19937 rng(7);  // (white noise of readingNoise uT per component, the same every run)
    std::normal_distribution<double> noise(0.0, readingNoise > 0 ? readingNoise : 1.0);
    std::vector<graphslam::NodeRecord>& records = w.records;
    std::vector<bool> kidnapped;  // per node: the first after a kidnap
    double yaw = 0;
    int segment = 0;
    for (std::size_t i = 0; i + 1 < corners.size(); ++i) {
        const Eigen::Vector2d d = corners[i + 1] - corners[i];
        const bool carry = static_cast<int>(i) == carried;
        if (carry) {
            // Put down at the leg's end, facing the next leg.
            const Eigen::Vector2d next = corners[i + 2] - corners[i + 1];
            yaw += std::remainder(std::atan2(next.y(), next.x()) - yaw, 2 * M_PI);
            graphslam::NodeRecord rec;
            rec.timestamp = static_cast<double>(records.size());
            rec.segment = ++segment;
            records.push_back(rec);
            kidnapped.push_back(true);
            w.truth.emplace_back(corners[i + 1].x(), corners[i + 1].y(), yaw);
            continue;
        }
        yaw += std::remainder(std::atan2(d.y(), d.x()) - yaw, 2 * M_PI);
        const int nodes = static_cast<int>(std::lround(d.norm() / 0.1));
        for (int k = (i == 0 ? 0 : 1); k <= nodes; ++k) {
            graphslam::NodeRecord rec;
            rec.timestamp = static_cast<double>(records.size());
            rec.segment = segment;
            kidnapped.push_back(false);
            for (int back = 9; back >= 0; --back) {
                const double f = (k - back / 10.0) / nodes;
                const Eigen::Vector2d at = corners[i] + std::max(f, 0.0) * d;
                for (const auto& mount : mounts) {
                    graphslam::MagneticSample m;
                    m.timestamp = rec.timestamp - 0.1 * back;
                    m.sensorLabel = mount.label;
                    m.sensorPose = mrpt::poses::CPose3D(0, mount.left, 0.3, 0, 0, 0);
                    const Eigen::Vector2d side(-std::sin(yaw), std::cos(yaw));
                    m.field = field.reading(at + mount.left * side, yaw);
                    if (readingNoise > 0)
                        for (int c = 0; c < 3; ++c) m.field[c] += noise(rng);
                    rec.magnetic.push_back(m);
                }
            }
            records.push_back(rec);
            const Eigen::Vector2d p = corners[i] + d * (double(k) / nodes);
            w.truth.emplace_back(p.x(), p.y(), yaw);
        }
    }
    std::vector<ScriptedNRD::Step>& steps = w.steps;
    for (std::size_t i = 1; i < w.truth.size(); ++i) {
        mrpt::poses::CPosePDFGaussian z;
        z.cov.setZero();
        if (kidnapped[i]) {
            z.cov(0, 0) = z.cov(1, 1) = z.cov(2, 2) = 100.0 * 100.0;  // anywhere
        } else {
            z.mean = w.truth[i] - w.truth[i - 1];
            z.cov(0, 0) = z.cov(1, 1) = 2e-4;
            z.cov(2, 2) = 2e-6;
        }
        steps.push_back({graphslam::planarConstraint(z), records[i].segment});
    }
    return w;
}

}  // namespace lodestone::test
