#pragma once

#include <string>
#include <vector>

namespace lodestone::io {

/** One kidnap as the simulator knows it: the ground truth a relocalization is judged by. */
struct KidnapEventRecord {
    int index{0};          ///< 1, 2, ... in time order
    double liftTime{0};    ///< [s since the epoch]
    double putDownTime{0};
    double x{0}, y{0}, yaw{0};  ///< put-down pose [m, m, rad], world frame
};

/** Writes `path` ("kidnap INDEX LIFT PUT_DOWN X Y YAW" per line, '#' comments) with a header
 * naming `scenario`. Throws std::runtime_error naming the file if it cannot be written. */
void writeKidnapEvents(const std::string& path, const std::string& scenario,
                       const std::vector<KidnapEventRecord>& events);

/** Reads such a file; a malformed line is a std::runtime_error naming file and line. */
std::vector<KidnapEventRecord> readKidnapEvents(const std::string& path);

}  // namespace lodestone::io
