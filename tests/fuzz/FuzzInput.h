#pragma once
// What the fuzz targets share: the input written to a file (Lodestone's readers take paths,
// as users give them), split into several files, and the rawlog walk every reader's user
// does. A target's verdict is "no crash": every std::exception is a clean refusal; a signal,
// a sanitizer report, an uncaught exception, a leak, a timeout or memory past libFuzzer's
// limits is a finding.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace lodestone::fuzz {

/** A folder of this process's own under $TMPDIR (or /tmp), made once. */
const std::string& scratchDir();

/** Writes `bytes` to scratchDir()/name (replacing it) and returns the path. */
std::string writeScratch(const std::string& name, const std::uint8_t* data, std::size_t size);
std::string writeScratch(const std::string& name, const std::string& bytes);

/** Splits the input at each line "%%" into at most `parts` pieces (missing ones empty): how a
 * target that reads several files (Aalto's three CSVs, TUM's lists) gets them from one input. */
std::vector<std::string> splitParts(const std::uint8_t* data, std::size_t size, std::size_t parts);

/** Reads a rawlog as the apps do: every entry through RawlogReader and described as
 * lodestone-inspect prints it, then the whole file through RawlogSource (what lodestone-slam
 * reads). Read errors end each walk; nothing else is caught. */
void walkRawlog(const std::string& path);

/** gzip (RFC 1952) compression of `bytes`, as a .rawlog.gz holds them. */
std::string gzipCompress(const std::uint8_t* data, std::size_t size);

}  // namespace lodestone::fuzz
