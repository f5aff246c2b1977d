// A TUM RGB-D sequence folder (lodestone-import tum): rgb.txt, depth.txt and groundtruth.txt
// are the input split at lines "%%". The images the lists name do not exist (an error once a
// pair is associated): the lists' parsing and the association are what is fuzzed.
#include <lodestone/datasets/TumRgbdImport.h>
#include <lodestone/obs/registerAllClasses.h>

#include <filesystem>

#include "../FuzzInput.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace lodestone;
    registerAllClasses();
    const auto parts = fuzz::splitParts(data, size, 3);
    fuzz::writeScratch("rgb.txt", parts[0]);
    fuzz::writeScratch("depth.txt", parts[1]);
    const std::string truth = fuzz::scratchDir() + "/groundtruth.txt";
    if (parts[2].empty()) {
        std::filesystem::remove(truth);
    } else {
        fuzz::writeScratch("groundtruth.txt", parts[2]);
    }
    try {
        datasets::importTumRgbd(fuzz::scratchDir(), fuzz::scratchDir() + "/out.rawlog", datasets::TumImportOptions{});
    } catch (const std::exception&) {
    }
    return 0;
}
