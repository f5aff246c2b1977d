// MagneticWindowERD's loaded map, thinned (closure::redundantReadings): a map reading whose
// line an earlier pass of the map already holds is read as part of windows but is not a target
// itself, so a map costs what the ground it covers costs, not what every session that drove it
// again added.
#include <lodestone/graphslam/erd/magnetic/MagneticWindowERD.h>
#include <lodestone/graphslam/erd/magnetic/PassThinning.h>

namespace lodestone::graphslam {

void MagneticWindowERD::thinMap() {
    if (!(params_.mapThinningRadius > 0)) return;
    for (auto& [label, sensor] : sensors_) thinTrack(sensor);
}

void MagneticWindowERD::thinTrack(Sensor& sensor) {
    const auto& samples = sensor.track->samples();
    std::vector<closure::PlacedReading> readings;  // the map's: they come first
    for (std::size_t i = 0; i < samples.size() && samples[i].node < map_nodes_; ++i)
        readings.push_back({positionAtSample(*sensor.track, i), samples[i].s, samples[i].segment});
    // (a window reaches n - 1 readings before the one it ends at, or after the one it starts at)
    sensor.redundant = closure::redundantReadings(readings, n_ - 1, params_.mapThinningRadius,
                                                  params_.minTravelGap,
                                                  [this](int a, int b) { return sameFrame(a, b); });
    sensor.nextTarget.assign(readings.size(), readings.size());
    for (std::size_t i = readings.size(); i-- > 0;)
        sensor.nextTarget[i] =
            sensor.redundant[i]
                ? (i + 1 < readings.size() ? sensor.nextTarget[i + 1] : readings.size())
                : i;
    stats_.mapReadings += readings.size();
    for (const char r : sensor.redundant) stats_.mapReadingsThinned += r;
}

}  // namespace lodestone::graphslam
