// A rawlog file, plain: MRPT's object framing and every class MRPT and Lodestone register,
// read as lodestone-inspect and lodestone-slam read it.
#include "../FuzzInput.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    lodestone::fuzz::walkRawlog(lodestone::fuzz::writeScratch("input.rawlog", data, size));
    return 0;
}
