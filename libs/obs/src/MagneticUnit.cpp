#include <lodestone/obs/MagneticUnit.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace lodestone::obs {

MagneticUnit MagneticUnit::normalized(double localField_uT) {
    char text[64];
    std::snprintf(text, sizeof text, "normalized:%g", localField_uT);
    return {localField_uT, text};
}

MagneticUnit MagneticUnit::parse(const std::string& text) {
    if (text == "gauss" || text == "G") return gauss();
    if (text == "uT" || text == "microtesla") return microtesla();
    if (text == "T" || text == "tesla") return tesla();
    for (const std::string prefix : {"normalized:", "xsens:"}) {
        if (text.rfind(prefix, 0) != 0) continue;
        const std::string number = text.substr(prefix.size());
        std::size_t used = 0;
        double localField = 0;
        try {
            localField = std::stod(number, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used != number.size() || !std::isfinite(localField) || localField <= 0) {
            throw std::invalid_argument("magnetic unit '" + text + "': expected " + prefix +
                                        "<local field strength in uT > 0>");
        }
        return normalized(localField);
    }
    throw std::invalid_argument("unknown magnetic unit '" + text + "' (expected " +
                                kMagneticUnitChoices + ")");
}

std::optional<std::string> implausibleFieldMagnitude(std::vector<double> magnitudes_uT) {
    magnitudes_uT.erase(std::remove_if(magnitudes_uT.begin(), magnitudes_uT.end(),
                                       [](double m) { return !std::isfinite(m); }),
                        magnitudes_uT.end());
    if (magnitudes_uT.empty()) return std::nullopt;
    const auto mid = magnitudes_uT.begin() + std::ptrdiff_t(magnitudes_uT.size() / 2);
    std::nth_element(magnitudes_uT.begin(), mid, magnitudes_uT.end());
    const double median = *mid;
    if (median >= kPlausibleFieldMin_uT && median <= kPlausibleFieldMax_uT) return std::nullopt;
    // Which unit the numbers fit: the one that brings the median nearest 45 uT (in log).
    std::string guess;
    if (median > 0) {
        struct Candidate {
            double uTPerUnit;
            const char* name;
        };
        double best = INFINITY;
        for (const Candidate c : {Candidate{100.0, "gauss"}, Candidate{1e6, "T"},
                                  Candidate{1e-3, "nT"}, Candidate{45.0, "normalized"}}) {
            const double miss = std::abs(std::log(median * c.uTPerUnit / 45.0));
            if (miss < best) {
                best = miss;
                guess = c.name;
            }
        }
        guess = " - as " + guess + " they would be";
        if (guess.find("nT") != std::string::npos)
            guess = " - they look like nanotesla (divide by 1000)";
        else if (guess.find("normalized") != std::string::npos)
            guess = " - they look like normalized units (normalized:<the field strength at "
                    "calibration in uT>)";
        else
            guess += " plausible";
    }
    char text[256];
    std::snprintf(text, sizeof text,
                  "the field's median magnitude is %.4g uT, implausible for Earth's field "
                  "(20-70 uT; taken as uT between %g and %g)",
                  median, kPlausibleFieldMin_uT, kPlausibleFieldMax_uT);
    return std::string(text) + guess;
}

}  // namespace lodestone::obs
