// The magnetic recording importers (lodestone-import kok / aalto): the first byte picks Kok &
// Solin's walk CSV or an Aalto trial, whose time, location and field CSVs are the rest split
// at lines "%%".
#include <lodestone/datasets/MagneticRecording.h>

#include "../FuzzInput.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace lodestone;
    if (size == 0) return 0;
    try {
        if ((data[0] & 1) == 0) {
            datasets::readKokWalk(fuzz::writeScratch("walk.csv", data + 1, size - 1));
        } else {
            const auto parts = fuzz::splitParts(data + 1, size - 1, 3);
            fuzz::writeScratch("1-time.csv", parts[0]);
            fuzz::writeScratch("1-loc.csv", parts[1]);
            fuzz::writeScratch("1-mag.csv", parts[2]);
            datasets::readAaltoTrial(fuzz::scratchDir(), 1);
        }
    } catch (const std::exception&) {
    }
    return 0;
}
