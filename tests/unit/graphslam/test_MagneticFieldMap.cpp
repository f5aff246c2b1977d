// MagneticGpERD's field map on a scripted run through a field over the plane: the robot drives
// a 12 m x 4 m loop twice, the second lap 0.3 m beside the first along the side where the field
// has its anomalies, with odometry that drifts (a heading bias and a scale error, claimed
// honestly). Where the sequence matcher places little, the field map must place the second
// lap - right along the path, and across it within what its covariance admits.
#include <gtest/gtest.h>
#include <lodestone/graphslam/erd/magnetic/MagneticGpERD.h>
#include <lodestone/graphslam/SlamEngine.h>

#include "PlaneField.h"
#include "ScriptedMagneticRun.h"

using namespace lodestone;

namespace {

struct Run {
    std::unique_ptr<graphslam::SlamEngine> engine;
    const graphslam::MagneticGpERD* erd{nullptr};
    std::vector<mrpt::poses::CPose2D> truth;
};

Run run(unsigned seed, const std::string& ini) {
    // Anomalies 0.4-0.8 m wide along the south side (y in [-1.5, 1.5]); the rest is plain.
    const test::PlaneField field(seed, -1, 13, 60, 0.4, 0.8);
    const double step = 0.1;
    Run r;
    std::vector<graphslam::NodeRecord> records;
    for (int lap = 0; lap < 2; ++lap) {
        const double y0 = 0.3 * lap;  // the second lap passes beside the first
        const double corners[5][2] = {{0, y0}, {12, y0}, {12, 4}, {0, 4}, {0, y0}};
        for (int side = 0; side < 4; ++side) {
            const double x0 = corners[side][0], ya = corners[side][1];
            const double dx = corners[side + 1][0] - x0, dy = corners[side + 1][1] - ya;
            const double len = std::hypot(dx, dy), yaw = std::atan2(dy, dx);
            const int nodes = static_cast<int>(std::lround(len / step));
            for (int k = (records.empty() ? 0 : 1); k <= nodes; ++k) {
                const double f = double(k) / nodes;
                graphslam::NodeRecord rec;
                rec.timestamp = static_cast<double>(records.size());
                for (int back = 9; back >= 0; --back) {
                    const double fr = std::max(0.0, f - back * step / (10 * len));
                    const Eigen::VectorXd b = field.at({x0 + fr * dx, ya + fr * dy});
                    graphslam::MagneticSample m;
                    m.timestamp = rec.timestamp - 0.1 * back;
                    m.sensorLabel = "MAG";
                    m.field = mrpt::math::TVector3D(b[0] - 20, 0, b[1]);
                    rec.magnetic.push_back(m);
                }
                records.push_back(rec);
                r.truth.emplace_back(x0 + f * dx, ya + f * dy, yaw);
            }
        }
    }
    // Odometry: 1 % long and turning 0.1 deg per metre too far, claimed within its noise (and
    // the heading drift in the INI): the gate stays inside what the field map searches.
    std::vector<test::ScriptedNRD::Step> steps;
    for (std::size_t i = 1; i < r.truth.size(); ++i) {
        const auto d = r.truth[i] - r.truth[i - 1];
        const double len = std::hypot(d.x(), d.y());
        mrpt::poses::CPosePDFGaussian z;
        z.mean = mrpt::poses::CPose2D(1.01 * d.x(), 1.01 * d.y(), d.phi() + 0.1 * M_PI / 180 * len);
        z.cov.setZero();
        z.cov(0, 0) = z.cov(1, 1) = 2e-4;
        z.cov(2, 2) = 2e-6;
        steps.push_back({graphslam::planarConstraint(z), 0});
    }
    auto run = test::runMagneticScript(std::move(steps), std::move(records), ini);
    r.engine = std::move(run.engine);
    r.erd = run.erd;
    return r;
}

// The field's own hyperparameters (what lodestone-magfit would fit on it).
const std::string kIni =
    "[MagneticGpERD]\nalignment = path\ngp_sigma_f = 4.0\ngp_length_scale = 0.6\n"
    "gp_sigma_n = 0.2\ngate_heading_drift = 0.002\nmap_search = true\n";

}  // namespace

TEST(MagneticGpERD, TheFieldMapPlacesALapBesideTheFirstAlongItAndHonestlyAcross) {
    std::size_t placed = 0;
    for (unsigned seed : {3u, 4u, 5u}) {
        const auto r = run(seed, kIni);
        for (const auto& rec : r.erd->records()) {
            if (!rec.fieldMap) continue;
            for (std::size_t k = 0; k < rec.edges.size(); ++k) {
                const auto [target, query] = rec.edges[k];
                const auto& m = rec.constraints[k].mean;
                const auto implied = r.truth[target] + mrpt::poses::CPose2D(m.x(), m.y(), m.yaw());
                // In the target's frame: x along its path, y across. One straight earlier pass
                // predicts the same field on either side of it, so across the closure may be
                // unsure - but it must say so (the error inside its 3-sigma ellipse); along the
                // path it must be right.
                const double c = std::cos(r.truth[target].phi()), sn = std::sin(r.truth[target].phi());
                const Eigen::Vector2d world(implied.x() - r.truth[query].x(),
                                            implied.y() - r.truth[query].y());
                const Eigen::Vector2d e(c * world.x() + sn * world.y(), -sn * world.x() + c * world.y());
                const auto& info = rec.constraints[k].cov_inv;
                Eigen::Matrix2d I2;
                I2 << info(0, 0), info(0, 1), info(1, 0), info(1, 1);
                EXPECT_LT(std::abs(e.x()), 0.15) << "seed " << seed << " edge " << target << " -> " << query;
                EXPECT_LT(e.dot(I2 * e), 11.83) << "seed " << seed << " edge " << target << " -> " << query
                                                << " error " << e.transpose();
                ++placed;
            }
        }
        EXPECT_GT(r.erd->stats().mapAccepted, 0u) << "seed " << seed;
    }
    EXPECT_GT(placed, 10u);
}

TEST(MagneticGpERD, WithoutTheFieldMapTheSameRunIsLeftToTheSequenceMatcher) {
    // The control: map_search off searches nothing (and the records say so).
    const auto r = run(3, kIni + "map_search = false\n");
    EXPECT_EQ(r.erd->stats().mapSearches, 0u);
    for (const auto& rec : r.erd->records()) EXPECT_FALSE(rec.fieldMap);
}
