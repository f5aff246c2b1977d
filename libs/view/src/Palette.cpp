#include <lodestone/plot/Colormap.h>
#include <lodestone/view/Palette.h>

#include <functional>
#include <map>

namespace lodestone::view {

namespace {
mrpt::img::TColor fromBgr(const cv::Scalar& bgr) {
    return mrpt::img::TColor(static_cast<std::uint8_t>(bgr[2]), static_cast<std::uint8_t>(bgr[1]),
                             static_cast<std::uint8_t>(bgr[0]));
}
}  // namespace

mrpt::img::TColor segmentColour(int segment) {
    return fromBgr(plot::seriesColour(static_cast<std::size_t>(segment < 0 ? 0 : segment)));
}

mrpt::img::TColor closerColour(const std::string& closer) {
    // The shipped closers by name (visual green as graph.png draws accepted closures); any
    // other by a hash of its name into the series colours.
    static const std::map<std::string, mrpt::img::TColor> known{
        {"OrbSubmapERD", {0, 170, 0}},          {"ProximityERD", {0, 190, 190}},
        {"MagneticWindowERD", {200, 0, 200}},   {"MagneticGpERD", {240, 140, 0}},
        {"MagneticCrossingERD", {120, 70, 230}}, {"closure", {0, 170, 0}},
        {"relocation", {255, 215, 0}},
    };
    const auto it = known.find(closer);
    if (it != known.end()) return it->second;
    return fromBgr(plot::seriesColour(std::hash<std::string>()(closer) % 10));
}

mrpt::img::TColor odometryColour() { return {0, 80, 200}; }
mrpt::img::TColor refusedColour() { return {230, 0, 0}; }
mrpt::img::TColor truthColour() { return {150, 150, 150}; }

}  // namespace lodestone::view
