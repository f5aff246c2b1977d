// A TUM trajectory file (lodestone-eval's and lodestone-slam's --ground-truth input).
#include <lodestone/io/TumTrajectory.h>

#include "../FuzzInput.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        lodestone::io::readTumTrajectory(lodestone::fuzz::writeScratch("trajectory.tum", data, size));
    } catch (const std::exception&) {
    }
    return 0;
}
