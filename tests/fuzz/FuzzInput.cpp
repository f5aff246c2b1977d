#include "FuzzInput.h"

#include <lodestone/inspect/EntryText.h>
#include <lodestone/io/RawlogReadError.h>
#include <lodestone/io/RawlogReader.h>
#include <lodestone/io/RawlogSource.h>
#include <lodestone/obs/registerAllClasses.h>
#include <unistd.h>
#include <zlib.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace lodestone::fuzz {

namespace {
/** The folder, removed with what is in it when the process ends normally. */
struct ScratchDir {
    ScratchDir() {
        const char* tmp = std::getenv("TMPDIR");
        const std::filesystem::path base = tmp && *tmp ? tmp : "/tmp";
        path = (base / ("lodestone-fuzz-" + std::to_string(::getpid()))).string();
        std::filesystem::create_directories(path);
    }
    ~ScratchDir() {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
    std::string path;
};
}  // namespace

const std::string& scratchDir() {
    static const ScratchDir dir;
    return dir.path;
}

std::string writeScratch(const std::string& name, const std::uint8_t* data, std::size_t size) {
    const std::string path = scratchDir() + "/" + name;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!out) throw std::runtime_error("fuzz: cannot write " + path);
    return path;
}

std::string writeScratch(const std::string& name, const std::string& bytes) {
    return writeScratch(name, reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
}

std::vector<std::string> splitParts(const std::uint8_t* data, std::size_t size, std::size_t parts) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    std::vector<std::string> out;
    std::size_t start = 0;
    while (out.size() + 1 < parts) {
        const auto at = text.find("\n%%\n", start);
        if (at == std::string::npos) break;
        out.push_back(text.substr(start, at + 1 - start));
        start = at + 4;
    }
    out.push_back(text.substr(start));
    out.resize(parts);
    return out;
}

void walkRawlog(const std::string& path) {
    registerAllClasses();
    try {
        io::RawlogReader reader(path);
        std::ostringstream text;
        while (auto entry = reader.next()) {
            inspect::describeEntry(*entry->object, text);
            text.str({});
        }
    } catch (const io::RawlogReadError&) {
    }
    try {
        io::RawlogSource source(path);
        while (auto obs = source.next()) {
        }
    } catch (const io::RawlogReadError&) {
    }
}

std::string gzipCompress(const std::uint8_t* data, std::size_t size) {
    z_stream z{};
    if (deflateInit2(&z, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
        throw std::runtime_error("fuzz: deflateInit2");
    }
    std::string out(deflateBound(&z, size) + 32, '\0');
    z.next_in = const_cast<Bytef*>(data);
    z.avail_in = static_cast<uInt>(size);
    z.next_out = reinterpret_cast<Bytef*>(out.data());
    z.avail_out = static_cast<uInt>(out.size());
    const int rc = deflate(&z, Z_FINISH);
    out.resize(z.total_out);
    deflateEnd(&z);
    if (rc != Z_STREAM_END) throw std::runtime_error("fuzz: deflate");
    return out;
}

}  // namespace lodestone::fuzz
