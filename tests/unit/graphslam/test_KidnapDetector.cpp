#include <lodestone/graphslam/nrd/KidnapDetector.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <gtest/gtest.h>

#include <random>

using namespace lodestone;
using graphslam::kidnap::KidnapDetector;
using odometry::FusedOdometry;

namespace {

constexpr double kDt = 1.0 / 30;  // frames at 30 Hz

KidnapDetector::Params bothOn() {
    KidnapDetector::Params p;
    p.motion = p.magnetic = true;
    return p;
}

mrpt::poses::CPosePDFGaussian gaussian(double x, double y, double yaw, double sxy, double syaw) {
    mrpt::poses::CPosePDFGaussian g;
    g.mean = mrpt::poses::CPose2D(x, y, yaw);
    g.cov.setZero();
    g.cov(0, 0) = g.cov(1, 1) = sxy * sxy;
    g.cov(2, 2) = syaw * syaw;
    return g;
}

/** A frame: the wheels moved `wheelStep` [m] forward since the last frame; VO, measured against
 * the previous frame, saw the robot move `voStep` forward and rise `rise` [m]. */
FusedOdometry::Estimate frame(double t, double wheelStep, std::optional<double> voStep,
                              double rise = 0) {
    FusedOdometry::Estimate e;
    e.timestamp = t;
    e.wheel = gaussian(wheelStep, 0, 0, 0.001 + 0.02 * wheelStep, 0.001);
    if (voStep) {
        e.visual.referenceTimestamp = t - kDt;
        e.visualSinceReference = gaussian(*voStep, 0, 0, 0.005, 0.002);
        e.visualRise = rise;
        e.visualRiseVariance = 0.005 * 0.005;
    }
    return e;
}

}  // namespace

TEST(KidnapDetector, DrivingWithAgreeingVisualOdometryIsNoKidnap) {
    KidnapDetector d(bothOn());
    std::mt19937 rng(3);
    std::normal_distribution<double> noise(0, 0.003);
    for (int i = 0; i < 900; ++i) {
        const double step = 0.01;  // 0.3 m/s
        EXPECT_FALSE(d.onFrame(frame(i * kDt, step, step + noise(rng)))) << "frame " << i;
    }
    EXPECT_EQ(d.stats().lifts, 0u);
}

TEST(KidnapDetector, ACarriedCameraWithTheWheelsStillIsALift) {
    KidnapDetector d(bothOn());
    int i = 0;
    for (; i < 60; ++i) ASSERT_FALSE(d.onFrame(frame(i * kDt, 0.01, 0.01)));
    const double liftTime = i * kDt;
    std::optional<KidnapDetector::Event> ev;
    // Carried at 0.5 m/s, the encoders frozen.
    for (; i < 90 && !ev; ++i) ev = d.onFrame(frame(i * kDt, 0, 0.0167));
    ASSERT_TRUE(ev.has_value());
    EXPECT_TRUE(ev->lifted);
    EXPECT_EQ(ev->by, "motion");
    EXPECT_NEAR(ev->time, liftTime, 0.2);
    EXPECT_TRUE(d.lifted());
    // Put down: the wheels drive again and VO agrees; the put-down is where driving resumed.
    for (; i < 150; ++i) ASSERT_FALSE(d.onFrame(frame(i * kDt, 0, 0.0167)));
    const double driving = i * kDt;
    std::optional<KidnapDetector::Event> down;
    for (; i < 200 && !down; ++i) down = d.onFrame(frame(i * kDt, 0.01, 0.01));
    ASSERT_TRUE(down.has_value());
    EXPECT_FALSE(down->lifted);
    EXPECT_NEAR(down->time, driving, 1e-9);
}

TEST(KidnapDetector, WheelsTurningInTheAirAndACameraThatRisesAreLifts) {
    KidnapDetector air(bothOn());
    std::optional<KidnapDetector::Event> ev;
    for (int i = 0; i < 90 && !ev; ++i) ev = air.onFrame(frame(i * kDt, 0.01, i < 30 ? 0.01 : 0.0));
    ASSERT_TRUE(ev.has_value());
    EXPECT_EQ(ev->by, "motion");

    KidnapDetector rise(bothOn());
    ev.reset();
    for (int i = 0; i < 60 && !ev; ++i) ev = rise.onFrame(frame(i * kDt, 0.0, 0.0, i < 30 ? 0 : 0.08));
    ASSERT_TRUE(ev.has_value());
    EXPECT_EQ(ev->by, "rise");
    // Driving, the same rise is taken for a VO error, not a lift.
    KidnapDetector driving(bothOn());
    for (int i = 0; i < 60; ++i)
        EXPECT_FALSE(driving.onFrame(frame(i * kDt, 0.01, 0.01, i < 30 ? 0 : 0.08))) << i;
}

TEST(KidnapDetector, TheFieldChangingUnderStillWheelsIsALift) {
    std::mt19937 rng(5);
    std::normal_distribution<double> noise(0, 0.3);
    KidnapDetector still(bothOn()), lifted(bothOn());
    // Standing still for 5 s: the field stays; no camera answers (a blank wall).
    for (int k = 0; k < 150; ++k) {
        const double t = k * kDt;
        ASSERT_FALSE(still.onFrame(frame(t, 0, std::nullopt)));
        ASSERT_FALSE(lifted.onFrame(frame(t, 0, std::nullopt)));
        for (int m = 0; m < 3; ++m) {
            const double tm = t + m * 0.01;
            EXPECT_FALSE(still.onMagnetic(tm, 48 + noise(rng)));
            // Lifted at 2 s: the floor's steel falls away, |B| drifts 3 uT/s.
            const auto ev = lifted.onMagnetic(tm, 48 + noise(rng) + (tm > 2 ? 3 * (tm - 2) : 0));
            if (ev) {
                EXPECT_EQ(ev->by, "magnetic");
                EXPECT_NEAR(ev->time, 2.0, 1.0);
            }
        }
    }
    EXPECT_EQ(still.stats().lifts, 0u);
    EXPECT_EQ(lifted.stats().lifts, 1u);
}

TEST(KidnapDetector, OffByDefaultAndConfigurationIsStrict) {
    EXPECT_FALSE(KidnapDetector(KidnapDetector::Params{}).enabled());
    mrpt::config::CConfigFileMemory ini("[kidnap_detection]\nmotion = true\npersistence = 5\n");
    const auto p = KidnapDetector::readParams(ini);
    EXPECT_TRUE(p.motion);
    EXPECT_FALSE(p.magnetic);
    EXPECT_EQ(p.persistence, 5);
    mrpt::config::CConfigFileMemory typo("[kidnap_detection]\nmotoin = true\n");
    EXPECT_THROW(KidnapDetector::readParams(typo), std::exception);
    mrpt::config::CConfigFileMemory bad("[kidnap_detection]\nlatency = 0.1\n");
    EXPECT_THROW(KidnapDetector::readParams(bad), std::exception);
}
