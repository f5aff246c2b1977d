#pragma once

#include <lodestone/io/RawlogReadError.h>
#include <lodestone/io/RawlogSource.h>
#include <lodestone/io/RawlogWriter.h>

#include <fstream>
#include <string>
#include <vector>

namespace lodestone::test {

inline void writeRawlog(const std::string& path,
                        const std::vector<mrpt::obs::CObservation::Ptr>& observations,
                        int gzipLevel = 0) {
    lodestone::io::RawlogWriter writer(path, {gzipLevel});
    for (const auto& o : observations) writer.write(*o);
    writer.close();
}

/** Everything a source yields, and the error that ended it (empty when it ended cleanly). */
struct Drained {
    std::vector<mrpt::obs::CObservation::Ptr> observations;
    std::string error;
    std::size_t errorEntry{0};
    std::uint64_t errorOffset{0};
};

inline Drained drain(lodestone::io::DataSource& source) {
    Drained d;
    try {
        while (auto o = source.next()) d.observations.push_back(o);
    } catch (const lodestone::io::RawlogReadError& e) {
        d.error = e.what();
        d.errorEntry = e.entryIndex();
        d.errorOffset = e.byteOffset();
    }
    return d;
}

inline std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void writeBytes(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace lodestone::test
