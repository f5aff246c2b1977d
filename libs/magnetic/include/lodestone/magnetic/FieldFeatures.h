#pragma once

#include <Eigen/Core>
#include <string>

namespace lodestone::magnetic {

/** What of the field a supernode holds.
 * - `Invariant`: |B| and the vertical component B_z. Neither depends on the heading, so a
 *   drifting odometry heading cannot spoil them (the default).
 * - `Vector`: the full field in the map frame, turned there with the estimated heading. More
 *   information, but only as good as the heading. */
enum class FieldMode { Invariant, Vector };

/** "invariant" | "vector"; throws std::invalid_argument naming the text otherwise. */
FieldMode parseFieldMode(const std::string& text);
std::string toString(FieldMode mode);
int channelsOf(FieldMode mode);

/** The feature of one reading: `robotField` [uT] in the levelled robot frame (z up), `heading`
 * the robot's estimated heading [rad] (Vector mode only). */
Eigen::VectorXd fieldFeature(const Eigen::Vector3d& robotField, double heading, FieldMode mode);

/** A reading worth keeping: finite and not saturated (|component| below `saturation` uT). */
bool usableReading(const Eigen::Vector3d& field, double saturation);

}  // namespace lodestone::magnetic
