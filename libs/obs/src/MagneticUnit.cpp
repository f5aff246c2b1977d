#include <lodestone/obs/MagneticUnit.h>

#include <cmath>
#include <stdexcept>

namespace lodestone::obs {

MagneticUnit MagneticUnit::parse(const std::string& text) {
    if (text == "gauss" || text == "G") return gauss();
    if (text == "uT" || text == "microtesla") return microtesla();
    if (text == "T" || text == "tesla") return tesla();
    const std::string xsensPrefix = "xsens:";
    if (text.rfind(xsensPrefix, 0) == 0) {
        const std::string number = text.substr(xsensPrefix.size());
        std::size_t used = 0;
        double localField = 0;
        try {
            localField = std::stod(number, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used != number.size() || !std::isfinite(localField) || localField <= 0) {
            throw std::invalid_argument("magnetic unit '" + text +
                                        "': expected xsens:<local field strength in uT > 0>");
        }
        return xsensNormalized(localField);
    }
    throw std::invalid_argument("unknown magnetic unit '" + text +
                                "' (expected gauss, uT, T or xsens:<local field in uT>)");
}

}  // namespace lodestone::obs
