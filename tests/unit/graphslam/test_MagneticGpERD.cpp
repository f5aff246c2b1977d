// MagneticGpERD's candidate gate and ambiguity resolution on a scripted run: a stretch driven
// east along y = 0 carries a field pattern; a parallel stretch `separation` metres north, also
// driven east, carries a look-alike. After a long detour the robot drives the south stretch
// again: its true match is the first south pass; the north one is a decoy, far (outside the
// position gate) or near (inside), an exact copy (undecidable) or a copy with anomalies of its
// own (the GP's likelihood tells them apart).
#include <gtest/gtest.h>
#include <lodestone/graphslam/erd/magnetic/MagneticGpERD.h>
#include <lodestone/graphslam/SlamEngine.h>

#include <random>

#include "ScriptedMagneticRun.h"

using namespace lodestone;

namespace {

/** A 1-D field pattern along a side: (|B| offset, B_z offset) bumps, 3 per metre. */
struct Pattern {
    struct Bump {
        double at, magnitude, vertical, width;
    };
    std::vector<Bump> bumps;
    Pattern(unsigned seed, double length, double amplitude) {
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> where(0, length), size(-amplitude, amplitude),
            width(0.15, 0.4);
        for (int k = 0; k < static_cast<int>(3 * length); ++k)
            bumps.push_back({where(rng), size(rng), size(rng), width(rng)});
    }
    Eigen::Vector2d at(double s) const {
        Eigen::Vector2d v(0, 0);
        for (const auto& b : bumps) {
            const double g = std::exp(-0.5 * (s - b.at) * (s - b.at) / (b.width * b.width));
            v += Eigen::Vector2d(b.magnitude * g, b.vertical * g);
        }
        return v;
    }
};

struct Decoy {
    double separation{20};       ///< [m] north of the south side
    double extra{0};             ///< [uT] amplitude of the decoy's own anomalies (0: exact copy)
    bool freshThirdPass{false};  ///< the second south pass sees a new random field instead
};

struct MagRun {
    std::unique_ptr<graphslam::SlamEngine> engine;
    const graphslam::MagneticGpERD* erd{nullptr};
    std::vector<mrpt::poses::CPose2D> truth;
};

struct Script {
    std::vector<test::ScriptedNRD::Step> steps;
    std::vector<graphslam::NodeRecord> records;
    std::vector<mrpt::poses::CPose2D> truth;
};

Script script(const Decoy& decoy) {
    const double side = 12.0, step = 0.1, n = decoy.separation;
    const Pattern south(3, side, 6.0), extra(4, side, decoy.extra), legs(5, 300.0, 6.0),
        fresh(6, side, 6.0);
    // The path: east along the south side (y = 0, from 5 m before it); round by the south and
    // west to the north side (y = n), east along it (the look-alike, its 5 m lead-in the same
    // as the south side's); a long detour round by the north and west
    // back to the start; east along the south side again. Every other stretch has a field of
    // its own. While the robot drives the look-alike the odometry is still sure of itself: the
    // south side is outside the gate; by the second south pass it has grown.
    enum class Field { LeadIn, South, Decoy, Legs, Again };
    struct Leg {
        double x0, y0, x1, y1;
        Field field;
    };
    const std::vector<Leg> path = {{-5, 0, 0, 0, Field::LeadIn},
                                   {0, 0, side, 0, Field::South},
                                   {side, 0, side, -5, Field::Legs},
                                   {side, -5, -5, -5, Field::Legs},
                                   {-5, -5, -5, n, Field::Legs},
                                   {-5, n, 0, n, Field::LeadIn},
                                   {0, n, side, n, Field::Decoy},
                                   {side, n, side, n + 10, Field::Legs},
                                   {side, n + 10, -10, n + 10, Field::Legs},
                                   {-10, n + 10, -10, -10, Field::Legs},
                                   {-10, -10, 0, -10, Field::Legs},
                                   {0, -10, 0, 0, Field::Legs},
                                   {0, 0, side, 0, Field::Again}};
    Script r;
    std::vector<graphslam::NodeRecord>& records = r.records;
    double legTravel = 0;  // along the detours, for their own field
    for (std::size_t li = 0; li < path.size(); ++li) {
        const auto& leg = path[li];
        const double len = std::hypot(leg.x1 - leg.x0, leg.y1 - leg.y0);
        const double yaw = std::atan2(leg.y1 - leg.y0, leg.x1 - leg.x0);
        const int nodes = static_cast<int>(std::lround(len / step));
        for (int k = (li == 0 ? 0 : 1); k <= nodes; ++k) {
            const double s = k * step;
            graphslam::NodeRecord rec;
            rec.timestamp = static_cast<double>(records.size());
            // Ten readings per node (a 100 Hz magnetometer at 1 m/s): many per resampling bin.
            for (int back = 9; back >= 0; --back) {
                const double sr = s - back * step / 10;
                Eigen::Vector2d f;
                switch (leg.field) {
                    case Field::LeadIn:
                        f = legs.at(250 + sr);
                        break;  // the same before both
                    case Field::South:
                        f = south.at(sr);
                        break;
                    case Field::Decoy:
                        f = south.at(sr) + extra.at(sr);
                        break;
                    case Field::Again:
                        f = decoy.freshThirdPass ? fresh.at(sr) : south.at(sr);
                        break;
                    case Field::Legs:
                        f = legs.at(legTravel + sr);
                        break;
                }
                graphslam::MagneticSample m;
                m.timestamp = rec.timestamp - 0.1 * back;
                m.sensorLabel = "MAG";
                // The invariant feature is (|B|, B_z): both carry the pattern.
                m.field = mrpt::math::TVector3D(30 + f.x(), 0, -40 + f.y());
                rec.magnetic.push_back(m);
            }
            records.push_back(rec);
            r.truth.emplace_back(leg.x0 + (leg.x1 - leg.x0) * s / len,
                                 leg.y0 + (leg.y1 - leg.y0) * s / len, yaw);
        }
        if (leg.field == Field::Legs) legTravel += len;
    }
    // Odometry: the truth's increments, with the noise an odometry would claim.
    std::vector<test::ScriptedNRD::Step>& steps = r.steps;
    for (std::size_t i = 1; i < r.truth.size(); ++i) {
        mrpt::poses::CPosePDFGaussian z;
        z.mean = r.truth[i] - r.truth[i - 1];
        z.cov.setZero();
        // (claimed so that the gate, 3 sigma of the drift plus its 0.5 m floor, is narrower
        // than the separation when the look-alike is first driven, wider on the second south
        // pass)
        z.cov(0, 0) = z.cov(1, 1) = 2e-4;
        z.cov(2, 2) = 2e-6;
        steps.push_back({graphslam::planarConstraint(z), 0});
    }
    return r;
}

MagRun run(const Decoy& decoy, const std::string& ini) {
    auto sc = script(decoy);
    MagRun r;
    r.truth = sc.truth;
    auto run = test::runMagneticScript(std::move(sc.steps), std::move(sc.records), ini);
    r.engine = std::move(run.engine);
    r.erd = run.erd;
    return r;
}

const std::string kIni = "[MagneticGpERD]\nalignment = path\ngate_heading_drift = 0\n";
// The same with the field map searching too: it must not be fooled where the sequence matcher
// is not.
const std::string kIniWithMap = kIni + "map_search = true\n";

/** Every closure of the run: how many land within `tolerance` of the truth, how many tie a
 * node to the look-alike (y near the separation). */
struct Verdict {
    std::size_t closures{0}, right{0}, toDecoy{0};
};
Verdict judge(const MagRun& r, double tolerance = 0.3) {
    Verdict v;
    for (const auto& rec : r.erd->records()) {
        for (std::size_t k = 0; k < rec.edges.size(); ++k) {
            const auto [target, query] = rec.edges[k];
            ++v.closures;
            const auto& m = rec.constraints[k].mean;
            const auto implied = r.truth[target] + mrpt::poses::CPose2D(m.x(), m.y(), m.yaw());
            const double error =
                std::hypot(implied.x() - r.truth[query].x(), implied.y() - r.truth[query].y());
            v.right += error <= tolerance;
            v.toDecoy += std::abs(r.truth[target].y() - r.truth[query].y()) > 1.0;
        }
    }
    return v;
}

/** The same judgement of every closure the engine was proposed, for any decider. */
Verdict judgeProposals(const graphslam::SlamEngine& engine,
                       const std::vector<mrpt::poses::CPose2D>& truth, double tolerance = 0.3) {
    Verdict v;
    for (const auto& p : engine.proposals()) {
        const auto& c = p.closure;
        ++v.closures;
        const auto& m = c.constraint.mean;
        const auto implied = truth[c.from] + mrpt::poses::CPose2D(m.x(), m.y(), m.yaw());
        v.right +=
            std::hypot(implied.x() - truth[c.to].x(), implied.y() - truth[c.to].y()) <= tolerance;
        v.toDecoy += std::abs(truth[c.from].y() - truth[c.to].y()) > 0.6;
    }
    return v;
}

/** The decoy run through MagneticWindowERD (its defaults, the gate's heading drift off as for
 * the GP decider; `extraIni` added). */
Verdict runWindow(const Decoy& decoy, graphslam::MagneticWindowERD::Stats* stats = nullptr,
                  const std::string& extraIni = "") {
    auto sc = script(decoy);
    const auto r = test::runMagneticScript<graphslam::MagneticWindowERD>(
        std::move(sc.steps), std::move(sc.records),
        "[MagneticWindowERD]\ngate_heading_drift = 0\n" + extraIni);
    if (stats) *stats = r.erd->stats();
    return judgeProposals(*r.engine, sc.truth);
}

// Every null model the window closer has: the decoys fool none of them.
const char* const kNullModels[] = {"null_model = window\n", "null_model = building\n"};

}  // namespace

TEST(MagneticWindowERD, ALookAlikeOutsideTheGateIsNotMatched) {
    for (const char* null : kNullModels) {
        Decoy d;
        d.separation = 20;
        const auto v = runWindow(d, nullptr, null);
        EXPECT_GT(v.closures, 5u) << null;
        EXPECT_EQ(v.toDecoy, 0u) << null;
        EXPECT_EQ(v.right, v.closures) << null;
    }
}

TEST(MagneticWindowERD, InsideTheGateTheLikelierPlaceIsChosen) {
    for (const char* null : kNullModels) {
        Decoy d;
        d.separation = 2.5;
        d.extra = 1.0;
        const auto v = runWindow(d, nullptr, null);
        EXPECT_GT(v.closures, 5u) << null;
        EXPECT_EQ(v.toDecoy, 0u) << null;
        EXPECT_EQ(v.right, v.closures) << null;
    }
}

// An exact copy inside the gate: the field cannot tell the places apart, the position prior
// can (the copy lies 3 sigma out; the GP decider, which ignores where in the gate a place is,
// finds them equally likely and closes nothing). Only where the prior alone reaches
// min_posterior is a closure made, and then to the true place.
TEST(MagneticWindowERD, AnExactCopyInsideTheGateIsToldApartByThePositionPriorOnly) {
    for (const char* null : kNullModels) {
        Decoy d;
        d.separation = 2.5;
        d.extra = 0;
        graphslam::MagneticWindowERD::Stats stats;
        const auto v = runWindow(d, &stats, null);
        EXPECT_GT(stats.ambiguous, 0u) << null;
        EXPECT_EQ(v.toDecoy, 0u) << null;
        EXPECT_EQ(v.right, v.closures) << null;
    }
}

TEST(MagneticWindowERD, AFieldNeverSeenBeforeGivesNoClosure) {
    for (const char* null : kNullModels) {
        Decoy d;
        d.separation = 20;
        d.freshThirdPass = true;
        EXPECT_EQ(runWindow(d, nullptr, null).closures, 0u) << null;
    }
}

TEST(MagneticGpERD, ALookAlikeOutsideTheGateIsNotMatchedNorMakesTheTrueOneAmbiguous) {
    for (const auto& ini : {kIni, kIniWithMap}) {
        Decoy d;
        d.separation = 20;
        const auto r = run(d, ini);
        const auto v = judge(r);
        EXPECT_GT(v.closures, 10u);
        EXPECT_EQ(v.toDecoy, 0u);
        EXPECT_EQ(v.right, v.closures);
        EXPECT_GT(r.erd->stats().gatedOut, 0u);
    }
}

TEST(MagneticGpERD, AnAlignmentsEdgesShareItsOneError) {
    // One alignment, subdivided into n node-to-node edges: each as sure as the alignment
    // (paper 000 §2.3), or, sharing it, each n times looser - together one alignment's worth.
    Decoy d;
    d.separation = 20;
    const auto alone = run(d, kIni);
    const auto shared = run(d, kIni + "edges_share_alignment = true\n");
    ASSERT_FALSE(alone.erd->records().empty());
    ASSERT_FALSE(shared.erd->records().empty());
    // (the first alignment: nothing the looser edges changed in the graph came before it)
    const auto& a = alone.erd->records().front();
    const auto& b = shared.erd->records().front();
    ASSERT_EQ(a.edges, b.edges);
    const auto n = static_cast<double>(a.edges.size());
    ASSERT_GT(n, 2);
    for (std::size_t k = 0; k < a.edges.size(); ++k) {
        EXPECT_EQ(a.constraints[k].mean, b.constraints[k].mean);
        const Eigen::Matrix<double, 6, 6> ia = a.constraints[k].cov_inv.asEigen(),
                                          ib = b.constraints[k].cov_inv.asEigen();
        // x, y and yaw carry the alignment's information (z, roll, pitch: the planar stiffness)
        for (const int r : {0, 1, 3})
            for (const int c : {0, 1, 3})
                EXPECT_NEAR(ib(r, c) * n, ia(r, c), 1e-6 * std::abs(ia(r, c)) + 1e-9);
    }
    EXPECT_GT(shared.erd->stats().edges, 10u);
    const auto v = judge(shared);
    EXPECT_EQ(v.right, v.closures);
}

TEST(MagneticGpERD, InsideTheGateTheLikelierPlaceIsChosen) {
    for (const auto& ini : {kIni, kIniWithMap}) {
        Decoy d;
        d.separation = 2.5;
        d.extra = 1.0;  // the decoy has anomalies of its own: the GP fits the true place better
        const auto r = run(d, ini);
        const auto v = judge(r);
        EXPECT_GT(r.erd->stats().resolved, 0u);
        EXPECT_GT(v.closures, 10u);
        EXPECT_EQ(v.toDecoy, 0u);
        EXPECT_EQ(v.right, v.closures);
    }
}

TEST(MagneticGpERD, TwoEquallyLikelyPlacesInsideTheGateGiveNoClosure) {
    for (const auto& ini : {kIni, kIniWithMap}) {
        Decoy d;
        d.separation = 2.5;
        d.extra = 0;  // an exact copy: nothing tells them apart
        const auto r = run(d, ini);
        const auto v = judge(r);
        EXPECT_GT(r.erd->stats().ambiguous, 0u);
        EXPECT_EQ(v.toDecoy, 0u);
        EXPECT_EQ(v.closures, 0u);
    }
}

TEST(MagneticGpERD, AFieldNeverSeenBeforeGivesNoClosure) {
    for (const auto& ini : {kIni, kIniWithMap}) {
        Decoy d;
        d.separation = 20;
        d.freshThirdPass = true;
        const auto r = run(d, ini);
        EXPECT_EQ(judge(r).closures, 0u) << ini;
    }
}
