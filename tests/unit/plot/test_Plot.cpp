#include <gtest/gtest.h>
#include <lodestone/plot/Axes.h>
#include <lodestone/plot/Colormap.h>
#include <lodestone/plot/PlaneMap.h>
#include <lodestone/plot/Ticks.h>

#include <cmath>

using namespace lodestone::plot;

TEST(Ticks, NiceStepsCoverTheRange) {
    EXPECT_EQ(niceTicks(0, 1, 6), (std::vector<double>{0, 0.2, 0.4, 0.6000000000000001, 0.8, 1}));
    const auto t = niceTicks(-3.7, 41.2, 6);
    ASSERT_GE(t.size(), 3u);
    EXPECT_DOUBLE_EQ(t[1] - t[0], 10.0);
    EXPECT_GE(t.front(), -3.7);
    EXPECT_LE(t.back(), 41.2);
    EXPECT_EQ(niceTicks(5, 5).size(), 1u);
    EXPECT_TRUE(niceTicks(0, std::nan("")).empty());
    EXPECT_LE(niceTicks(0, 1e6, 4).size(), 4u);
}

TEST(Ticks, LabelsCarryTheDecimalsTheStepNeeds) {
    EXPECT_EQ(tickLabel(0.25, 0.05), "0.25");
    EXPECT_EQ(tickLabel(20, 10), "20");
    EXPECT_EQ(tickLabel(-1.5, 0.5), "-1.5");
}

TEST(Colormap, EndsAreViridisAndNanIsGrey) {
    const Colormap c(40, 60);
    const cv::Vec3b low = c(0), high = c(1000), mid = c(50), nan = c(std::nan(""));
    EXPECT_EQ(low, c(40));    // clamped
    EXPECT_EQ(high, c(60));
    EXPECT_GT(low[0], low[2]);    // dark purple-blue: blue over red
    EXPECT_GT(high[2], high[0]);  // yellow: red over blue
    EXPECT_NE(mid, low);
    EXPECT_EQ(nan, cv::Vec3b(160, 160, 160));
}

TEST(ScalarGrid, AveragesPerCellAndQuantiles) {
    ScalarGrid g(0.5);
    g.add(0.1, 0.1, 10);
    g.add(0.4, 0.2, 20);   // same cell
    g.add(-0.1, 0.1, 50);  // the cell to the left
    g.add(std::nan(""), 0, 1);
    EXPECT_EQ(g.values(), 3u);
    EXPECT_EQ(g.cells(), 2u);
    double sum = 0;
    g.forEach([&](double x0, double, double x1, double, double mean, std::size_t n) {
        EXPECT_DOUBLE_EQ(x1 - x0, 0.5);
        sum += mean * static_cast<double>(n);
        EXPECT_DOUBLE_EQ(mean, x0 < 0 ? 50 : 15);
    });
    EXPECT_DOUBLE_EQ(sum, 80);
    EXPECT_DOUBLE_EQ(g.quantile(0), 15);
    EXPECT_DOUBLE_EQ(g.quantile(1), 50);
    const Bounds b = g.bounds();
    EXPECT_DOUBLE_EQ(b.x0, -0.5);
    EXPECT_DOUBLE_EQ(b.x1, 0.5);
}

TEST(Axes, PixelsAndDataRoundTripAndEqualAspect) {
    cv::Mat3b canvas(400, 800, cv::Vec3b(255, 255, 255));
    Axes a(canvas, cv::Rect(0, 0, 800, 400));
    a.setLimitsEqualAspect(Bounds{0, 1, 0, 1});
    const auto& l = a.limits();
    const double perPixelX = (l.x1 - l.x0) / (a.plotArea().width - 1);
    const double perPixelY = (l.y1 - l.y0) / (a.plotArea().height - 1);
    EXPECT_NEAR(perPixelX / perPixelY, 1.0, 0.01);
    const cv::Point p = a.toPixel(0.3, 0.7);
    const cv::Point2d back = a.toData(p);
    EXPECT_NEAR(back.x, 0.3, perPixelX);
    EXPECT_NEAR(back.y, 0.7, perPixelY);
    // y grows upwards on screen.
    EXPECT_LT(a.toPixel(0, 1).y, a.toPixel(0, 0).y);
    // A far-away point is clipped, not an overflow.
    a.line({{0.5, 0.5}, {1e12, 1e12}}, cv::Scalar(0, 0, 255));
    a.drawFrame("t", "x", "y");
    int red = 0;
    for (const auto& px : canvas) red += px[2] > 200 && px[0] < 120 && px[1] < 120;
    EXPECT_GT(red, 10);
}

TEST(Ticks, ARangeOfAFewUlpsEndsWithOneTick) {
    // Found by a flat magnetic field: |B| quantiles 1e-14 apart made the tick loop stand still.
    const double lo = 47.434164902525694, hi = std::nextafter(std::nextafter(lo, 100.0), 100.0);
    EXPECT_EQ(niceTicks(lo, hi, 5).size(), 1u);
    EXPECT_LE(niceTicks(0, 1e-300, 5).size(), 6u);
}

TEST(Colormap, AFlatRangeStillDrawsItsBar) {
    const Colormap c(47.43, 47.43 + 1e-13);
    EXPECT_LT(c.lo(), 47.43);
    EXPECT_GT(c.hi(), 47.43);
    cv::Mat3b canvas(200, 200, cv::Vec3b(255, 255, 255));
    c.drawBar(canvas, cv::Rect(20, 20, 18, 150), "|B| [uT]");
    EXPECT_NE(canvas(100, 25), cv::Vec3b(255, 255, 255));
}
