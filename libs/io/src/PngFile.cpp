#include <lodestone/io/PngFile.h>

#include <libdeflate.h>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <vector>

namespace lodestone::io {

namespace {
std::uint32_t bigEndian32(const std::uint8_t* p) {
    return (std::uint32_t(p[0]) << 24) | (std::uint32_t(p[1]) << 16) | (std::uint32_t(p[2]) << 8) | p[3];
}

/** The Paeth predictor without branches: on a noisy image which of a, b, c it picks is a coin
 * toss, and a mispredicted branch a byte cost more than the rest of the decoding. */
inline int paeth(int a, int b, int c) {
    const int pa = std::abs(b - c), pb = std::abs(a - c), pc = std::abs(a + b - 2 * c);
    const int useB = -static_cast<int>(pb <= pc);
    const int notC = (b & useB) | (c & ~useB);
    const int useA = -static_cast<int>((pa <= pb) & (pa <= pc));
    return (a & useA) | (notC & ~useA);
}

/** Undoes one row's filter (PNG spec, section 9) in place, 3 bytes a pixel (the three channels
 * are independent: written per pixel, so the compiler can run them side by side). */
bool unfilterRgbRow(int filter, std::uint8_t* row, const std::uint8_t* above, std::size_t n) {
    switch (filter) {
        case 0:  // None
            return true;
        case 1:  // Sub
            for (std::size_t x = 3; x < n; x += 3) {
                row[x] = std::uint8_t(row[x] + row[x - 3]);
                row[x + 1] = std::uint8_t(row[x + 1] + row[x - 2]);
                row[x + 2] = std::uint8_t(row[x + 2] + row[x - 1]);
            }
            return true;
        case 2:  // Up
            if (above) {
                for (std::size_t x = 0; x < n; ++x) row[x] = std::uint8_t(row[x] + above[x]);
            }
            return true;
        case 3:  // Average
            if (!above) {
                for (std::size_t x = 3; x < n; ++x) row[x] = std::uint8_t(row[x] + (row[x - 3] >> 1));
                return true;
            }
            for (std::size_t x = 0; x < 3; ++x) row[x] = std::uint8_t(row[x] + (above[x] >> 1));
            for (std::size_t x = 3; x < n; ++x)
                row[x] = std::uint8_t(row[x] + ((row[x - 3] + above[x]) >> 1));
            return true;
        case 4:  // Paeth
            if (!above) return unfilterRgbRow(1, row, nullptr, n);  // (no row above: Sub)
            for (std::size_t x = 0; x < 3; ++x) row[x] = std::uint8_t(row[x] + above[x]);
            for (std::size_t x = 3; x < n; x += 3) {
                for (std::size_t k = x; k < x + 3; ++k) row[k] = std::uint8_t(row[k] + paeth(row[k - 3], above[k], above[k - 3]));
            }
            return true;
        default:
            return false;
    }
}

struct Decompressor {
    libdeflate_decompressor* d{libdeflate_alloc_decompressor()};
    ~Decompressor() { libdeflate_free_decompressor(d); }
};
}  // namespace

std::optional<cv::Mat> decodeRgbPng(const std::string& path) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) return std::nullopt;
    const std::streamoff length = in.tellg();
    if (length <= 0) return std::nullopt;
    std::vector<std::uint8_t> file(static_cast<std::size_t>(length));
    in.seekg(0);
    if (!in.read(reinterpret_cast<char*>(file.data()), length)) return std::nullopt;
    static constexpr std::array<std::uint8_t, 8> kSignature{137, 80, 78, 71, 13, 10, 26, 10};
    if (file.size() < 8 + 25 || !std::equal(kSignature.begin(), kSignature.end(), file.begin()))
        return std::nullopt;
    std::uint32_t width = 0, height = 0;
    std::vector<std::uint8_t> data;  // the IDAT chunks' contents, joined
    bool header = false, ended = false;
    for (std::size_t at = 8; at < file.size() && !ended;) {
        if (file.size() - at < 12) return std::nullopt;
        const std::uint32_t length = bigEndian32(&file[at]);
        if (length > file.size() - at - 12) return std::nullopt;
        const std::uint8_t* type = &file[at + 4];
        const std::uint8_t* body = &file[at + 8];
        if (libdeflate_crc32(0, type, length + 4) != bigEndian32(body + length)) return std::nullopt;
        const std::string name(reinterpret_cast<const char*>(type), 4);
        if (!header) {
            // IHDR first: 8-bit (8), truecolour (2), deflate (0), adaptive filters (0), no interlace (0).
            if (name != "IHDR" || length != 13 || body[8] != 8 || body[9] != 2 || body[10] != 0 ||
                body[11] != 0 || body[12] != 0)
                return std::nullopt;
            width = bigEndian32(body), height = bigEndian32(body + 4);
            header = true;
        } else if (name == "IDAT") {
            data.insert(data.end(), body, body + length);
        } else if (name == "IEND") {
            ended = true;
        } else if (name == "tRNS" || name == "PLTE" || !(type[0] & 0x20)) {
            return std::nullopt;  // transparency, a palette, or a critical chunk not known here
        }
        at += 12 + std::size_t(length);
    }
    // (larger than 8K x 4K: not a camera's frame; MRPT's reader, with its memory guard, decides)
    if (!ended || width == 0 || height == 0 || std::uint64_t(width) * height > (1u << 25))
        return std::nullopt;
    const std::size_t stride = std::size_t(width) * 3, size = (stride + 1) * height;
    // Deflate expands at most ~1032:1: a larger image than that is a damaged header.
    if (size > data.size() * 1040 + 1024) return std::nullopt;
    // Each row is its filter's byte then the row: unfiltered in place, then seen as an RGB
    // image whose rows are one byte further apart than their width.
    const std::unique_ptr<std::uint8_t[]> rows(new std::uint8_t[size]);
    Decompressor inflater;
    std::size_t got = 0;
    if (!inflater.d ||
        libdeflate_zlib_decompress(inflater.d, data.data(), data.size(), rows.get(), size, &got) !=
            LIBDEFLATE_SUCCESS ||
        got != size)
        return std::nullopt;
    for (std::uint32_t y = 0; y < height; ++y) {
        std::uint8_t* line = rows.get() + y * (stride + 1);
        const std::uint8_t* above = y > 0 ? line + 1 - (stride + 1) : nullptr;
        if (!unfilterRgbRow(line[0], line + 1, above, stride)) return std::nullopt;
    }
    const cv::Mat rgb(static_cast<int>(height), static_cast<int>(width), CV_8UC3, rows.get() + 1,
                      stride + 1);
    cv::Mat bgr;
    cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
    return bgr;
}

}  // namespace lodestone::io
