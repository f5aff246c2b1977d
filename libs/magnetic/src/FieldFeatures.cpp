#include <lodestone/magnetic/FieldFeatures.h>

#include <cmath>
#include <stdexcept>

namespace lodestone::magnetic {

FieldMode parseFieldMode(const std::string& text) {
    if (text == "invariant") return FieldMode::Invariant;
    if (text == "vector") return FieldMode::Vector;
    throw std::invalid_argument("field mode '" + text + "': expected invariant or vector");
}

std::string toString(FieldMode mode) {
    return mode == FieldMode::Invariant ? "invariant" : "vector";
}

int channelsOf(FieldMode mode) { return mode == FieldMode::Invariant ? 2 : 3; }

Eigen::VectorXd fieldFeature(const Eigen::Vector3d& b, double heading, FieldMode mode) {
    if (mode == FieldMode::Invariant) return Eigen::Vector2d(b.norm(), b.z());
    const double c = std::cos(heading), s = std::sin(heading);
    return Eigen::Vector3d(c * b.x() - s * b.y(), s * b.x() + c * b.y(), b.z());
}

bool usableReading(const Eigen::Vector3d& field, double saturation) {
    return field.allFinite() && field.cwiseAbs().maxCoeff() < saturation;
}

}  // namespace lodestone::magnetic
