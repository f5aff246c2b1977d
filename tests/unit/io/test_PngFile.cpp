// io::decodeRgbPng against OpenCV's (libpng's) decoding of the same files: the same pixels for
// the layout it takes, nothing for any other layout or a damaged file.
#include <gtest/gtest.h>
#include <libdeflate.h>
#include <lodestone/io/PngFile.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <fstream>

#include "TestPaths.h"

using lodestone::io::decodeRgbPng;

namespace {
void put32(std::vector<std::uint8_t>& out, std::uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<std::uint8_t>(v >> s));
}
void chunk(std::vector<std::uint8_t>& out, const char* type, const std::vector<std::uint8_t>& body) {
    put32(out, static_cast<std::uint32_t>(body.size()));
    std::vector<std::uint8_t> typed(type, type + 4);
    typed.insert(typed.end(), body.begin(), body.end());
    out.insert(out.end(), typed.begin(), typed.end());
    put32(out, libdeflate_crc32(0, typed.data(), typed.size()));
}
int paeth(int a, int b, int c) {
    const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
    return (pa <= pb && pa <= pc) ? a : (pb <= pc ? b : c);
}
/** An 8-bit RGB PNG of `bgr`, row y filtered with filter y % 5 (None, Sub, Up, Average, Paeth):
 * every filter the decoder must undo, whatever an encoder's heuristics would choose. */
std::vector<std::uint8_t> pngWithEveryFilter(const cv::Mat& bgr) {
    const int w = bgr.cols, h = bgr.rows, n = 3 * w;
    std::vector<std::uint8_t> raw;
    std::vector<int> prev(static_cast<std::size_t>(n), 0), cur(static_cast<std::size_t>(n));
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const auto p = bgr.at<cv::Vec3b>(y, x);
            cur[3 * x] = p[2], cur[3 * x + 1] = p[1], cur[3 * x + 2] = p[0];
        }
        const int f = y % 5;
        raw.push_back(static_cast<std::uint8_t>(f));
        for (int i = 0; i < n; ++i) {
            const int a = i >= 3 ? cur[i - 3] : 0, b = prev[i], c = i >= 3 ? prev[i - 3] : 0;
            const int pred = f == 0 ? 0 : f == 1 ? a : f == 2 ? b : f == 3 ? (a + b) / 2 : paeth(a, b, c);
            raw.push_back(static_cast<std::uint8_t>(cur[i] - pred));
        }
        prev = cur;
    }
    libdeflate_compressor* z = libdeflate_alloc_compressor(6);
    std::vector<std::uint8_t> packed(libdeflate_zlib_compress_bound(z, raw.size()));
    packed.resize(libdeflate_zlib_compress(z, raw.data(), raw.size(), packed.data(), packed.size()));
    libdeflate_free_compressor(z);
    std::vector<std::uint8_t> png{137, 80, 78, 71, 13, 10, 26, 10}, header;
    put32(header, static_cast<std::uint32_t>(w));
    put32(header, static_cast<std::uint32_t>(h));
    header.insert(header.end(), {8, 2, 0, 0, 0});
    chunk(png, "IHDR", header);
    chunk(png, "tEXt", {'K', 0, 'v'});  // (an ancillary chunk: skipped)
    // The data in two IDAT chunks: they are one stream.
    const std::size_t half = packed.size() / 2;
    chunk(png, "IDAT", {packed.begin(), packed.begin() + static_cast<long>(half)});
    chunk(png, "IDAT", {packed.begin() + static_cast<long>(half), packed.end()});
    chunk(png, "IEND", {});
    return png;
}
std::string write(const lodestone::test::TempDir& dir, const std::string& name,
                  const std::vector<std::uint8_t>& bytes) {
    const std::string path = dir.file(name);
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()),
                                                static_cast<std::streamsize>(bytes.size()));
    return path;
}
/** Noise (the simulator's frames) over gradients (a filter's predictions right and wrong). */
cv::Mat testImage(int w, int h) {
    cv::Mat img(h, w, CV_8UC3), noise(h, w, CV_8UC3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) img.at<cv::Vec3b>(y, x) = cv::Vec3b(x % 256, y % 256, (x * y) % 256);
    cv::randu(noise, 0, 24);
    return img + noise;
}
void expectSame(const cv::Mat& a, const cv::Mat& b) {
    ASSERT_EQ(a.type(), b.type());
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
}
}  // namespace

TEST(PngFile, EveryFilterUndoneAsLibpngUndoesIt) {
    lodestone::test::TempDir dir;
    const cv::Mat img = testImage(97, 41);  // (odd sizes: no row a multiple of anything)
    const std::string path = write(dir, "filters.png", pngWithEveryFilter(img));
    const auto ours = decodeRgbPng(path);
    ASSERT_TRUE(ours.has_value());
    expectSame(*ours, img);
    expectSame(*ours, cv::imread(path, cv::IMREAD_UNCHANGED));  // (as MRPT loads a file)
}

TEST(PngFile, WhatOpenCvWritesReadsBackTheSame) {
    lodestone::test::TempDir dir;
    const cv::Mat img = testImage(640, 480);
    const std::string path = dir.file("frame.png");
    ASSERT_TRUE(cv::imwrite(path, img));
    const auto ours = decodeRgbPng(path);
    ASSERT_TRUE(ours.has_value());
    expectSame(*ours, img);
}

TEST(PngFile, OtherLayoutsAndDamagedFilesAreLeftToMrpt) {
    lodestone::test::TempDir dir;
    const cv::Mat img = testImage(64, 48);
    cv::Mat grey, rgba, deep;
    cv::cvtColor(img, grey, cv::COLOR_BGR2GRAY);
    cv::cvtColor(img, rgba, cv::COLOR_BGR2BGRA);
    img.convertTo(deep, CV_16UC3, 256);
    for (const auto& [name, m] : {std::pair<std::string, cv::Mat>{"grey.png", grey},
                                  {"rgba.png", rgba}, {"deep.png", deep}}) {
        const std::string path = dir.file(name);
        ASSERT_TRUE(cv::imwrite(path, m));
        EXPECT_FALSE(decodeRgbPng(path).has_value()) << name;
    }
    EXPECT_FALSE(decodeRgbPng(dir.file("missing.png")).has_value());
    const std::vector<std::uint8_t> good = pngWithEveryFilter(img);
    ASSERT_TRUE(decodeRgbPng(write(dir, "good.png", good)).has_value());
    auto flipped = good;
    flipped[good.size() / 2] ^= 0x10;  // (inside the image data: its chunk's CRC fails)
    EXPECT_FALSE(decodeRgbPng(write(dir, "flipped.png", flipped)).has_value());
    const std::vector<std::uint8_t> cut(good.begin(), good.begin() + static_cast<long>(good.size() - 20));
    EXPECT_FALSE(decodeRgbPng(write(dir, "cut.png", cut)).has_value());
    auto notPng = good;
    notPng[1] = 'Q';
    EXPECT_FALSE(decodeRgbPng(write(dir, "signature.png", notPng)).has_value());
}
