#pragma once

#include <Eigen/Core>
#include <vector>

namespace lodestone::sim {

/** A point magnetic dipole: a lump of magnetized steel. */
struct MagneticDipole {
    Eigen::Vector3d position;  ///< [m], world frame
    Eigen::Vector3d moment;    ///< [A m^2]
};

/** An indoor magnetic field: a uniform earth field plus the fields of point dipoles (rebar,
 * beams and furniture are chains or clusters of them). Every term is the field of a magnetic
 * source outside the region where it is evaluated, so the sum is curl- and divergence-free
 * there, as a real ambient field is. Values in microtesla, world frame (x, y horizontal, z up).
 */
class MagneticField {
  public:
    /** Earth field from magnitude [uT], inclination [rad] (positive: pointing down, northern
     * hemisphere) and declination [rad] (angle of its horizontal part from world +x towards +y).
     */
    void setEarthField(double magnitude_uT, double inclination, double declination);
    void setEarthField(const Eigen::Vector3d& field_uT) { earth_ = field_uT; }
    void addDipole(const MagneticDipole& d) { dipoles_.push_back(d); }
    /** A straight chain of dipoles from a to b, `spacing` apart, each `momentPerMetre` *
     * spacing: a magnetized beam or a rebar line. */
    void addLine(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                 const Eigen::Vector3d& momentPerMetre, double spacing);

    /** Field at `p` [uT], world frame. */
    Eigen::Vector3d at(const Eigen::Vector3d& p) const;

    const Eigen::Vector3d& earthField() const { return earth_; }
    const std::vector<MagneticDipole>& dipoles() const { return dipoles_; }

    /** Field of one dipole at offset r = p - position [uT]:
     * mu0/(4 pi) (3 (m.r^) r^ - m) / |r|^3. Zero closer than 1 cm (inside the steel). */
    static Eigen::Vector3d dipoleField(const Eigen::Vector3d& moment, const Eigen::Vector3d& r);

  private:
    Eigen::Vector3d earth_{0, 0, 0};
    std::vector<MagneticDipole> dipoles_;
};

}  // namespace lodestone::sim
