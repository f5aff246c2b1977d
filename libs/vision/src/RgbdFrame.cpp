#include <lodestone/vision/RgbdFrame.h>

#include <stdexcept>

namespace lodestone::vision {

cv::Mat depthToMetres(const cv::Mat& raw16, double metresPerUnit) {
    if (raw16.type() != CV_16UC1)
        throw std::invalid_argument("depth image must be 16-bit, 1 channel");
    cv::Mat metres;
    raw16.convertTo(metres, CV_32F, metresPerUnit);
    return metres;
}

}  // namespace lodestone::vision
