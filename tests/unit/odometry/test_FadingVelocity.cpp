// The fading-velocity model (a Gauss-Markov velocity): its mean and variance against a Monte
// Carlo run of the process itself, and its two limits (constant velocity, random walk).
#include <gtest/gtest.h>
#include <lodestone/odometry/FadingVelocity.h>

#include <Eigen/Geometry>

#include <cmath>
#include <random>

using lodestone::odometry::FadingVelocity;

namespace {
/** The process itself, one axis, simulated `runs` times over `seconds` from `v0`: the mean and
 * variance of its displacement. Exact discretization of the velocity about the cruise c:
 * v' = c + a (v - c) + s w, a = e^-dt/tau, s^2 = sigma^2 (1 - a^2). */
void simulate(const FadingVelocity& model, double v0, double cruise, double seconds, unsigned seed,
              double& mean, double& variance) {
    const double dt = 1e-3;
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> n01;
    const double a = std::exp(-dt / model.correlationSeconds);
    const double s = model.speedSigma * std::sqrt(1 - a * a);
    const int runs = 4000;
    double sum = 0, sum2 = 0;
    for (int r = 0; r < runs; ++r) {
        double v = v0, x = 0;
        for (double t = 0; t < seconds - 1e-9; t += dt) {
            const double next = cruise + a * (v - cruise) + s * n01(rng);
            x += 0.5 * (v + next) * dt;
            v = next;
        }
        sum += x;
        sum2 += x * x;
    }
    mean = sum / runs;
    variance = sum2 / runs - mean * mean;
}
}  // namespace

TEST(FadingVelocity, MatchesTheProcessSimulated) {
    const FadingVelocity model{0.5, 1.0};
    const double v0 = 0.3, T = 3.0;
    double mean = 0, var = 0;
    simulate(model, v0, 0.0, T, 7, mean, var);
    const double modelMean = model.meanDisplacement(Eigen::Vector3d(v0, 0, 0), T).x();
    const double modelVar = model.displacementVariance(T);
    // Sampling error of the mean: sqrt(var / runs) ~ 0.014 m; of the variance ~ 2.2 % (5 and
    // 4.5 sigma allowed; the seed is fixed).
    EXPECT_NEAR(mean, modelMean, 0.07);
    EXPECT_NEAR(var / modelVar, 1.0, 0.1);
}

TEST(FadingVelocity, ShortGapsAreConstantVelocityLongOnesARandomWalk) {
    const FadingVelocity model{0.5, 1.0};
    const Eigen::Vector3d v0(0.3, -0.1, 0.0);
    // Short: the last velocity carried on, sigma as white-noise acceleration of
    // q = 2 sigma^2 / tau: var = q T^3 / 3.
    const double t = 0.01;
    // (the velocity has faded by t / 2 tau on average: second order)
    EXPECT_NEAR((model.meanDisplacement(v0, t) - v0 * t * (1 - t / 2)).norm(), 0, 1e-7);
    EXPECT_NEAR(model.displacementVariance(t) / (2 * 0.25 / 1.0 * t * t * t / 3), 1.0, 0.02);
    // Long: the mean stops at v0 tau, the variance grows as 2 sigma^2 tau T.
    EXPECT_NEAR((model.meanDisplacement(v0, 50) - v0).norm(), 0, 1e-9);
    EXPECT_NEAR(model.displacementVariance(100) / (2 * 0.25 * 100), 1.0, 0.03);
    // Continuous across the series' switch, zero at zero.
    EXPECT_NEAR(model.displacementVariance(0.999e-3) / model.displacementVariance(1.001e-3), 1.0, 0.01);
    EXPECT_EQ(model.displacementVariance(0), 0.0);
    EXPECT_EQ(model.meanDisplacement(v0, 0).norm(), 0.0);
}

// A start velocity known only to v0Sigma adds its own spread carried over the gap; not known at
// all (the stationary spread) the displacement is the stationary process's: 2 s^2 tau^2 (u - 1
// + e^-u).
TEST(FadingVelocity, AnUncertainStartVelocityWidensTheDisplacement) {
    const FadingVelocity model{0.5, 1.0};
    for (const double T : {0.2, 1.0, 4.0}) {
        const double u = T / model.correlationSeconds, carried = 1 - std::exp(-u);
        EXPECT_NEAR(model.displacementVariance(T, 0.03) - model.displacementVariance(T),
                    carried * carried * 0.03 * 0.03, 1e-12);
        EXPECT_NEAR(model.displacementVariance(T, model.speedSigma),
                    2 * 0.25 * (u - 1 + std::exp(-u)), 1e-12);
    }
}

// Across the carrier's heading the velocity fades with its own time constant: in the carrier's
// axes each of the step's terms is the along or the across model's, turned with the carrier
// into the state's frame; without it, every axis is the along model's, exactly as before.
TEST(FadingVelocity, AcrossTheHeadingTheVelocityFadesSooner) {
    using Matrix9d = Eigen::Matrix<double, 9, 9>;
    FadingVelocity model{0.5, 1.0};
    const double dt = 0.2;
    const Eigen::Matrix3d quarter =
        Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    Matrix9d F, Q, F0, Q0;
    model.step(dt).matrices(F0, Q0);
    model.matrices(dt, quarter, F, Q);
    EXPECT_EQ((F - F0).norm(), 0.0);
    EXPECT_EQ((Q - Q0).norm(), 0.0);

    model.acrossSeconds = 0.25;
    const auto along = model.step(dt), across = FadingVelocity{0.5, 0.25}.step(dt);
    model.matrices(dt, Eigen::Matrix3d::Identity(), F, Q);
    EXPECT_NEAR(F(3, 3), along.fade, 1e-15);
    EXPECT_NEAR(F(4, 4), across.fade, 1e-15);
    EXPECT_NEAR(F(5, 5), across.fade, 1e-15);
    EXPECT_NEAR(F(1, 4), across.carry, 1e-15);
    EXPECT_NEAR(Q(0, 0), along.qxx, 1e-15);
    EXPECT_NEAR(Q(1, 4), across.qxv, 1e-15);
    EXPECT_NEAR(Q(2, 2), across.qxx, 1e-15);
    // Turned a quarter about up, the carrier's heading is the state's y: a velocity along the
    // state's x is now across the heading and fades as such.
    model.matrices(dt, quarter, F, Q);
    EXPECT_NEAR(F(3, 3), across.fade, 1e-15);
    EXPECT_NEAR(F(4, 4), along.fade, 1e-15);
    EXPECT_NEAR(F(3, 4), 0.0, 1e-15);
    EXPECT_NEAR(Q(1, 1), along.qxx, 1e-15);
    EXPECT_LT(across.fade, 0.5);  // (0.2 s of 0.25: e^-0.8)
    EXPECT_GT(along.fade, 0.8);

    // The closed forms per axis agree: along x, across y and z.
    const Eigen::Vector3d v0(0.3, 0.13, 0.05);
    const Eigen::Vector3d mean = model.meanDisplacement(v0, 4.0);
    EXPECT_NEAR(mean.x(), (FadingVelocity{0.5, 1.0}.meanDisplacement(v0, 4.0).x()), 1e-15);
    EXPECT_NEAR(mean.y(), 0.13 * 0.25 * (1 - std::exp(-16.0)), 1e-12);
    const Eigen::Vector3d var = model.displacementVariances(4.0, 0.03);
    EXPECT_EQ(var.x(), model.displacementVariance(4.0, 0.03));
    EXPECT_EQ(var.y(), FadingVelocity({0.5, 0.25}).displacementVariance(4.0, 0.03));
    EXPECT_EQ(var.z(), var.y());
}

// The velocity itself across a gap, as the next gap starts from it: faded towards zero with the
// axis's time constant, its spread towards the carrier's. The process is Markov, so a gap cut
// in two (VO restarting in between and losing track again) carries the velocity to the same
// end as the whole gap does - and the displacement of the two halves adds up to the whole's.
TEST(FadingVelocity, ItsVelocityFadesAlikeInOneGapOrInTwo) {
    FadingVelocity model{0.5, 1.0, 0.25};
    const Eigen::Vector3d v0(0.3, 0.1, -0.05);
    const Eigen::Matrix3d C0 = 0.03 * 0.03 * Eigen::Matrix3d::Identity();
    Eigen::Vector3d whole = v0;
    Eigen::Matrix3d wholeC = C0;
    model.fadeVelocity(0.6, whole, wholeC);
    EXPECT_NEAR(whole.x(), 0.3 * std::exp(-0.6), 1e-12);
    EXPECT_NEAR(whole.y(), 0.1 * std::exp(-0.6 / 0.25), 1e-12);
    EXPECT_NEAR(wholeC(0, 0), std::exp(-1.2) * 0.03 * 0.03 + 0.25 * (1 - std::exp(-1.2)), 1e-12);

    Eigen::Vector3d halves = v0;
    Eigen::Matrix3d halvesC = C0;
    model.fadeVelocity(0.2, halves, halvesC);
    const Eigen::Vector3d first = model.meanDisplacement(v0, 0.2);
    const Eigen::Vector3d second = model.meanDisplacement(halves, 0.4);
    model.fadeVelocity(0.4, halves, halvesC);
    EXPECT_NEAR((halves - whole).norm(), 0, 1e-12);
    EXPECT_NEAR((halvesC - wholeC).norm(), 0, 1e-12);
    EXPECT_NEAR((first + second - model.meanDisplacement(v0, 0.6)).norm(), 0, 1e-12);

    // Long after, nothing of the start is left: zero, and the carrier's spread.
    Eigen::Vector3d late = v0;
    Eigen::Matrix3d lateC = C0;
    model.fadeVelocity(60, late, lateC);
    EXPECT_NEAR(late.norm(), 0, 1e-12);
    EXPECT_NEAR((lateC - 0.25 * Eigen::Matrix3d::Identity()).norm(), 0, 1e-12);
}

// With a cruise the velocity fades towards it, not towards rest: the process v = c + an
// Ornstein-Uhlenbeck deviation, simulated, against the model's mean and variance; and the
// variance is the zero-mean model's (the cruise moves the mean only).
TEST(FadingVelocity, WithACruiseTheVelocityFadesTowardsItNotTowardsRest) {
    const FadingVelocity model{0.5, 1.0};
    const double c = 0.3, v0 = 0.1, T = 4.0;
    double mean = 0, var = 0;
    simulate(model, v0, c, T, 11, mean, var);
    const Eigen::Vector3d cruise(c, 0, 0);
    const double modelMean = model.meanDisplacement(Eigen::Vector3d(v0, 0, 0), T, cruise).x();
    // (sampling error of the mean ~0.017 m; of the variance ~2.2 %)
    EXPECT_NEAR(mean, modelMean, 0.08);
    EXPECT_NEAR(var / model.displacementVariance(T), 1.0, 0.1);
    // Closed form: c T + (v0 - c) tau (1 - e^-T/tau) - far more than the rest model's v0 tau.
    EXPECT_NEAR(modelMean, c * T + (v0 - c) * (1 - std::exp(-T)), 1e-12);
    EXPECT_GT(modelMean, 5 * model.meanDisplacement(Eigen::Vector3d(v0, 0, 0), T).x());

    // The velocity itself: towards the cruise, its spread as without one; Markov still.
    Eigen::Vector3d whole(v0, 0.05, 0), halves = whole, rest = whole;
    Eigen::Matrix3d wholeC = 0.01 * Eigen::Matrix3d::Identity(), halvesC = wholeC, restC = wholeC;
    model.fadeVelocity(0.8, whole, wholeC, cruise);
    model.fadeVelocity(0.8, rest, restC);
    EXPECT_NEAR(whole.x(), c + (v0 - c) * std::exp(-0.8), 1e-12);
    EXPECT_NEAR((wholeC - restC).norm(), 0, 1e-12);
    const Eigen::Vector3d first = model.meanDisplacement(halves, 0.3, cruise);
    model.fadeVelocity(0.3, halves, halvesC, cruise);
    const Eigen::Vector3d second = model.meanDisplacement(halves, 0.5, cruise);
    model.fadeVelocity(0.5, halves, halvesC, cruise);
    EXPECT_NEAR((halves - whole).norm(), 0, 1e-12);
    EXPECT_NEAR((first + second - model.meanDisplacement(Eigen::Vector3d(v0, 0.05, 0), 0.8, cruise)).norm(),
                0, 1e-12);
    // Long after: the cruise.
    model.fadeVelocity(60, whole, wholeC, cruise);
    EXPECT_NEAR((whole - cruise).norm(), 0, 1e-12);
}

// The filter's step with a cruise (DepthBridge's prediction) is the model's: in the carrier's
// own axes, the step's drift added to F x gives meanDisplacement and fadeVelocity; turned, it
// turns with the carrier (the heading's time constant along its heading, not the map's x).
TEST(FadingVelocity, TheFiltersCruiseStepIsTheModels) {
    const FadingVelocity model{0.5, 1.0, 0.25};
    const Eigen::Vector3d v0(0.2, 0.04, -0.01), cruise(0.3, 0, 0);
    const double T = 0.7;
    for (const double yaw : {0.0, M_PI / 3}) {
        const Eigen::Matrix3d R = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
        Eigen::Matrix<double, 9, 9> F, Q;
        model.matrices(T, R, F, Q);
        Eigen::Matrix<double, 9, 1> x = Eigen::Matrix<double, 9, 1>::Zero();
        x.segment<3>(3) = R * v0;
        x = F * x + model.cruiseStep(T, R, cruise);
        Eigen::Vector3d v = v0;
        Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
        model.fadeVelocity(T, v, C, cruise);
        EXPECT_NEAR((x.head<3>() - R * model.meanDisplacement(v0, T, cruise)).norm(), 0, 1e-12) << yaw;
        EXPECT_NEAR((x.segment<3>(3) - R * v).norm(), 0, 1e-12) << yaw;
        EXPECT_EQ(x.tail<3>().norm(), 0.0);
    }
}
