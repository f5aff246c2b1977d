#include <lodestone/sim/MagneticField.h>

#include <cmath>

namespace lodestone::sim {

namespace {
constexpr double kMu0Over4PiInMicroTesla = 1e-7 * 1e6;  // mu0 / 4 pi [T m / A] -> [uT m / A]
}

void MagneticField::setEarthField(double magnitude_uT, double inclination, double declination) {
    const double horizontal = magnitude_uT * std::cos(inclination);
    earth_ = {horizontal * std::cos(declination), horizontal * std::sin(declination),
              -magnitude_uT * std::sin(inclination)};
}

void MagneticField::addLine(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& momentPerMetre, double spacing) {
    const double length = (b - a).norm();
    const int n = std::max(1, static_cast<int>(std::round(length / spacing)));
    const double step = length / n;
    for (int i = 0; i < n; ++i) {
        const double s = (i + 0.5) / n;  // the centre of each piece
        addDipole({a + s * (b - a), momentPerMetre * step});
    }
}

Eigen::Vector3d MagneticField::dipoleField(const Eigen::Vector3d& moment,
                                           const Eigen::Vector3d& r) {
    const double d2 = r.squaredNorm();
    if (d2 < 1e-4) return Eigen::Vector3d::Zero();
    const double d = std::sqrt(d2);
    const Eigen::Vector3d rhat = r / d;
    return kMu0Over4PiInMicroTesla * (3.0 * moment.dot(rhat) * rhat - moment) / (d2 * d);
}

Eigen::Vector3d MagneticField::at(const Eigen::Vector3d& p) const {
    Eigen::Vector3d b = earth_;
    for (const auto& d : dipoles_) b += dipoleField(d.moment, p - d.position);
    return b;
}

}  // namespace lodestone::sim
