#include "XwdImage.h"

#include <array>
#include <cstdint>
#include <fstream>
#include <set>
#include <stdexcept>
#include <vector>

namespace lodestone::test {

namespace {
// The XWD file header: 25 big-endian 32-bit words (X11/XWDFile.h, file version 7).
enum Field {
    kHeaderSize, kFileVersion, kPixmapFormat, kPixmapDepth, kWidth, kHeight, kXOffset,
    kByteOrder, kBitmapUnit, kBitmapBitOrder, kBitmapPad, kBitsPerPixel, kBytesPerLine,
    kVisualClass, kRedMask, kGreenMask, kBlueMask, kBitsPerRgb, kColormapEntries, kNColors,
    kFieldCount = 25
};
constexpr std::uint32_t kZPixmap = 2;
constexpr std::size_t kXColorBytes = 12;

int lowestBit(std::uint32_t mask) {
    int b = 0;
    while (mask && !(mask & 1u)) {
        mask >>= 1;
        ++b;
    }
    return b;
}
}  // namespace

cv::Mat3b readXwd(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot open");
    std::array<std::uint32_t, kFieldCount> h{};
    for (auto& word : h) {
        unsigned char b[4];
        if (!in.read(reinterpret_cast<char*>(b), 4)) throw std::runtime_error(path + ": short header");
        word = (std::uint32_t{b[0]} << 24) | (std::uint32_t{b[1]} << 16) | (std::uint32_t{b[2]} << 8) | b[3];
    }
    if (h[kFileVersion] != 7 || h[kPixmapFormat] != kZPixmap ||
        (h[kBitsPerPixel] != 24 && h[kBitsPerPixel] != 32) || h[kWidth] == 0 || h[kHeight] == 0 ||
        h[kWidth] > 16384 || h[kHeight] > 16384) {
        throw std::runtime_error(path + ": not a 24/32-bit ZPixmap XWD file");
    }
    // Window name after the header, then the colour map, then the pixels.
    in.seekg(static_cast<std::streamoff>(h[kHeaderSize] + h[kNColors] * kXColorBytes));
    const std::size_t bpp = h[kBitsPerPixel] / 8, stride = h[kBytesPerLine];
    if (stride < h[kWidth] * bpp) throw std::runtime_error(path + ": bytes per line too small");
    std::vector<unsigned char> row(stride);
    cv::Mat3b image(static_cast<int>(h[kHeight]), static_cast<int>(h[kWidth]));
    const bool msbFirst = h[kByteOrder] == 1;
    const int rs = lowestBit(h[kRedMask]), gs = lowestBit(h[kGreenMask]), bs = lowestBit(h[kBlueMask]);
    for (int y = 0; y < image.rows; ++y) {
        if (!in.read(reinterpret_cast<char*>(row.data()), static_cast<std::streamsize>(stride))) {
            throw std::runtime_error(path + ": file ends inside the pixels");
        }
        for (int x = 0; x < image.cols; ++x) {
            const unsigned char* p = row.data() + static_cast<std::size_t>(x) * bpp;
            std::uint32_t v = 0;
            for (std::size_t k = 0; k < bpp; ++k) {
                v |= std::uint32_t{p[msbFirst ? k : bpp - 1 - k]} << (8 * (bpp - 1 - k));
            }
            image(y, x) = cv::Vec3b(static_cast<unsigned char>((v & h[kBlueMask]) >> bs),
                                    static_cast<unsigned char>((v & h[kGreenMask]) >> gs),
                                    static_cast<unsigned char>((v & h[kRedMask]) >> rs));
        }
    }
    return image;
}

std::size_t distinctColours(const cv::Mat3b& image) {
    std::set<std::uint32_t> colours;
    for (int y = 0; y < image.rows; y += 4) {
        for (int x = 0; x < image.cols; x += 4) {
            const auto& c = image(y, x);
            colours.insert((std::uint32_t{c[2]} << 16) | (std::uint32_t{c[1]} << 8) | c[0]);
        }
    }
    return colours.size();
}

}  // namespace lodestone::test
