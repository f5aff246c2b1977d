// MagneticWindowERD's loaded map, prepared once its nodes are all in. Thinned
// (closure::redundantReadings): a map reading whose line an earlier pass of the map already
// holds is read as part of windows but is not a target itself, so a map costs what the ground
// it covers costs, not what every session that drove it again added. Projected: its target
// windows put in the displacement model's basis at once, not at a run's first query, which
// compares with every one of them while the run does not know where it is.
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

void MagneticWindowERD::projectMapTargets() {
    if (!params_.passDisplacement) return;  // (the basis serves the displacement model only)
    // The windows a query's scan compares with (query()): forward windows ending at a target of
    // the queried sensor's track, backward ones starting at a target of the mirror's (of the
    // queried track when there is no mirror).
    const auto project = [&](const Sensor& sensor, bool backward) {
        const auto& track = *sensor.track;
        const auto& samples = track.samples();
        for (std::size_t c = 0; c < samples.size() && samples[c].node < map_nodes_; ++c) {
            if (c < sensor.redundant.size() && sensor.redundant[c]) continue;
            const std::size_t start = backward ? c : c + 1 - n_;
            if (backward ? c + n_ > samples.size() : c + 1 < n_) continue;
            if (samples[start].segment != samples[start + n_ - 1].segment ||
                samples[start + n_ - 1].node >= map_nodes_)
                continue;
            projected_map_.emplace(projectionKey(track, start, backward),
                                   projectedWindow(track, start, backward));
        }
    };
    const auto own = sensors_.find(params_.sensorLabel);
    if (own == sensors_.end()) return;  // (a map without the sensor's readings: nothing to project)
    project(own->second, false);
    const auto mirror = mirror_.empty() ? own : sensors_.find(mirror_);
    if (mirror != sensors_.end()) project(mirror->second, true);
}

}  // namespace lodestone::graphslam
