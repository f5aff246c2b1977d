#pragma once

#include <lodestone/io/RawlogReadError.h>
#include <lodestone/io/RawlogSource.h>
#include <lodestone/io/RawlogWriter.h>
#include <mrpt/io/CFileOutputStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>

#include <fstream>
#include <functional>
#include <string>
#include <vector>

namespace lodestone::test {

/** A rawlog in MRPT's actions + sensory frames format: `count` pairs of an odometry action
 * (0.1 m forward, then `edit`ed) and a sensory frame holding `frame(k)`. */
inline void writeActionsAndFrames(
    const std::string& path, int count,
    const std::function<void(mrpt::obs::CActionRobotMovement2D&, int)>& edit,
    const std::function<mrpt::obs::CObservation::Ptr(int)>& frame) {
    mrpt::io::CFileOutputStream f(path);
    auto out = mrpt::serialization::archiveFrom(f);
    for (int k = 0; k < count; ++k) {
        mrpt::obs::CActionCollection actions;
        mrpt::obs::CActionRobotMovement2D move;
        move.computeFromOdometry(mrpt::poses::CPose2D(0.1, 0, 0), {});
        edit(move, k);
        actions.insert(move);
        mrpt::obs::CSensoryFrame sf;
        sf.insert(frame(k));
        out << actions << sf;
    }
}

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
