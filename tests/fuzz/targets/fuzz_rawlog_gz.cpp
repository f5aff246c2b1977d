// A .rawlog.gz: the first byte chooses between the rest gzip-compressed here (the entries
// reached through the gzip reader, its read-ahead and its size bounds) and the rest taken as
// the file's bytes (a damaged gzip stream).
#include "../FuzzInput.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace lodestone::fuzz;
    if (size == 0) return 0;
    const bool compressHere = (data[0] & 1) == 0;
    const std::string bytes = compressHere
        ? gzipCompress(data + 1, size - 1)
        : std::string(reinterpret_cast<const char*>(data + 1), size - 1);
    walkRawlog(writeScratch("input.rawlog.gz", bytes));
    return 0;
}
