#include <gtest/gtest.h>
#include <lodestone/io/TumTrajectory.h>

#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "EvalCommand.h"
#include "TestPaths.h"

using namespace lodestone;

using test::evalCmd;

TEST(EvalApp, ReportsTheMetricsAndDrawsThePlot) {
    test::TempDir dir;
    {
        io::TumTrajectoryWriter gt(dir.file("gt.tum")), est(dir.file("est.tum"));
        for (int i = 0; i <= 100; ++i) {
            const double t = 10 + 0.1 * i;
            gt.write(t, mrpt::poses::CPose3D(std::cos(0.05 * i), std::sin(0.05 * i), 0, 0, 0, 0));
            // The same circle, shifted (alignment removes it) and 2 cm off in y every other pose.
            est.write(t + 0.005,
                      mrpt::poses::CPose3D(5 + std::cos(0.05 * i),
                                           std::sin(0.05 * i) + (i % 2 ? 0.02 : 0.0), 0, 0, 0, 0));
        }
    }
    std::string out, err;
    ASSERT_EQ(
        evalCmd({dir.file("est.tum"), dir.file("gt.tum"), "--plot", dir.file("p.png")}, out, err),
        0)
        << err;
    EXPECT_NE(out.find("associated poses     101"), std::string::npos) << out;
    EXPECT_NE(out.find("ATE  RMSE 0.010"), std::string::npos) << out;  // +-1 cm about the mean
    const cv::Mat plot = cv::imread(dir.file("p.png"));
    EXPECT_FALSE(plot.empty());
}

TEST(EvalApp, BadInputAndUsage) {
    test::TempDir dir;
    std::string out, err;
    EXPECT_EQ(evalCmd({}, out, err), 2);
    EXPECT_EQ(evalCmd({dir.file("a.tum")}, out, err), 2);
    EXPECT_EQ(evalCmd({dir.file("a.tum"), dir.file("b.tum")}, out, err), 1);
    EXPECT_NE(err.find("a.tum"), std::string::npos) << err;
    {
        io::TumTrajectoryWriter a(dir.file("a.tum")), b(dir.file("b.tum"));
        a.write(1, {});
        b.write(50, {});
    }
    EXPECT_EQ(evalCmd({dir.file("a.tum"), dir.file("b.tum")}, out, err), 1);
    EXPECT_NE(err.find("associate"), std::string::npos) << err;
}
