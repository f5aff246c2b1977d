#include <lodestone/io/KidnapEvents.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace lodestone::io {

void writeKidnapEvents(const std::string& path, const std::string& scenario,
                       const std::vector<KidnapEventRecord>& events) {
    std::ofstream out(path);
    if (!out) throw std::runtime_error(path + ": cannot create");
    out << "# kidnaps of scenario '" << scenario << "'\n"
        << "# index lift_time put_down_time put_down_x put_down_y put_down_yaw"
           "  (times [s since the epoch], pose [m, m, rad], world frame)\n";
    for (const auto& e : events) {
        char line[200];
        std::snprintf(line, sizeof(line), "kidnap %d %.6f %.6f %.4f %.4f %.5f\n", e.index,
                      e.liftTime, e.putDownTime, e.x, e.y, e.yaw);
        out << line;
    }
    if (!out.flush()) throw std::runtime_error(path + ": write failed");
}

std::vector<KidnapEventRecord> readKidnapEvents(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open kidnap events file");
    std::vector<KidnapEventRecord> out;
    std::string line;
    for (int lineNo = 1; std::getline(in, line); ++lineNo) {
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#') continue;
        std::istringstream s(line);
        std::string word;
        KidnapEventRecord e;
        s >> word >> e.index >> e.liftTime >> e.putDownTime >> e.x >> e.y >> e.yaw;
        if (!s || word != "kidnap" || !std::isfinite(e.liftTime) || !std::isfinite(e.putDownTime) ||
            !(e.putDownTime >= e.liftTime) || !std::isfinite(e.x) || !std::isfinite(e.y) ||
            !std::isfinite(e.yaw)) {
            throw std::runtime_error(path + ": line " + std::to_string(lineNo) +
                                     ": expected 'kidnap INDEX LIFT PUT_DOWN X Y YAW'");
        }
        out.push_back(e);
    }
    return out;
}

}  // namespace lodestone::io
