#include <lodestone/sim/SurfaceTexture.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace lodestone::sim {

namespace {
cv::Scalar randomColour(Random& rng, int lo, int hi) {
    return cv::Scalar(rng.uniformInt(lo, hi), rng.uniformInt(lo, hi), rng.uniformInt(lo, hi));
}

// Posters, notices and frames: nested rectangles, discs, bars of "text" - many corners.
void drawPosters(cv::Mat3b& img, double pxm, Random& rng) {
    const double area = img.cols * img.rows / (pxm * pxm);
    const int count = std::max(1, static_cast<int>(area * 2.5));
    for (int i = 0; i < count; ++i) {
        const int w = static_cast<int>(rng.uniform(0.2, 0.8) * pxm);
        const int h = static_cast<int>(rng.uniform(0.2, 0.9) * pxm);
        const int x = rng.uniformInt(0, std::max(0, img.cols - w));
        const int y = rng.uniformInt(0, std::max(0, img.rows - h));
        const cv::Rect r(x, y, w, h);
        if (rng.uniform() < 0.4) {
            // A photograph: smooth random blobs (a coarse random grid, upsampled cubically).
            cv::Mat3b coarse(rng.uniformInt(4, 9), rng.uniformInt(4, 9));
            for (auto& px : coarse) {
                px = cv::Vec3b(static_cast<uchar>(rng.uniformInt(0, 255)),
                               static_cast<uchar>(rng.uniformInt(0, 255)),
                               static_cast<uchar>(rng.uniformInt(0, 255)));
            }
            cv::Mat3b photo;
            cv::resize(coarse, photo, r.size(), 0, 0, cv::INTER_CUBIC);
            photo.copyTo(img(r & cv::Rect(0, 0, img.cols, img.rows)));
        } else {
            cv::rectangle(img, r, randomColour(rng, 20, 235), cv::FILLED);
        }
        cv::rectangle(img, r, randomColour(rng, 0, 80), std::max(1, static_cast<int>(pxm * 0.01)));
        const int parts = rng.uniformInt(6, 16);
        for (int k = 0; k < parts; ++k) {
            const int pw = std::max(2, static_cast<int>(w * rng.uniform(0.1, 0.5)));
            const int ph = std::max(2, static_cast<int>(h * rng.uniform(0.05, 0.4)));
            const cv::Point p(x + rng.uniformInt(0, std::max(0, w - pw)),
                              y + rng.uniformInt(0, std::max(0, h - ph)));
            switch (rng.uniformInt(0, 2)) {
                case 0:
                    cv::rectangle(img, cv::Rect(p.x, p.y, pw, ph), randomColour(rng, 0, 255),
                                  cv::FILLED);
                    break;
                case 1:
                    cv::circle(img, p + cv::Point(pw / 2, ph / 2), std::min(pw, ph) / 2,
                               randomColour(rng, 0, 255), cv::FILLED);
                    break;
                default: {  // a line of "text": short dark bars
                    const int bar = std::max(2, static_cast<int>(pxm * 0.02));
                    for (int bx = p.x; bx + bar < p.x + pw; bx += bar + bar / 2 + 1) {
                        const int bh = std::max(2, static_cast<int>(ph * rng.uniform(0.2, 0.6)));
                        cv::rectangle(img, cv::Rect(bx, p.y, bar, bh), randomColour(rng, 0, 60),
                                      cv::FILLED);
                    }
                }
            }
        }
    }
}

void drawBricks(cv::Mat3b& img, double pxm, Random& rng) {
    const int bw = static_cast<int>(0.25 * pxm), bh = static_cast<int>(0.075 * pxm);
    const int mortar = std::max(1, static_cast<int>(0.01 * pxm));
    img.setTo(cv::Scalar(170, 180, 185));
    for (int row = 0, y = 0; y < img.rows; ++row, y += bh) {
        for (int x = (row % 2) ? -bw / 2 : 0; x < img.cols; x += bw) {
            const int shade = rng.uniformInt(-35, 35);
            cv::rectangle(img, cv::Rect(x + mortar, y + mortar, bw - mortar, bh - mortar),
                          cv::Scalar(60 + shade, 80 + shade, 150 + shade), cv::FILLED);
        }
    }
}

void drawTiles(cv::Mat3b& img, double pxm, const cv::Vec3b& base, Random& rng) {
    const int tile = static_cast<int>(0.5 * pxm);
    const int grout = std::max(1, static_cast<int>(0.008 * pxm));
    img.setTo(cv::Scalar(90, 90, 95));
    for (int y = 0; y < img.rows; y += tile) {
        for (int x = 0; x < img.cols; x += tile) {
            const int d = rng.uniformInt(-12, 12);
            cv::rectangle(img, cv::Rect(x + grout, y + grout, tile - grout, tile - grout),
                          cv::Scalar(base[0] + d, base[1] + d, base[2] + d), cv::FILLED);
            const int specks = rng.uniformInt(0, 3);  // scuffs and stains
            for (int s = 0; s < specks; ++s) {
                cv::circle(img, cv::Point(x + rng.uniformInt(0, tile), y + rng.uniformInt(0, tile)),
                           rng.uniformInt(1, std::max(2, tile / 20)), randomColour(rng, 40, 120),
                           cv::FILLED);
            }
        }
    }
}

// Paint: the base colour with a gentle, smooth unevenness (a few long-wavelength waves).
void drawPlain(cv::Mat3b& img, double pxm, const cv::Vec3b& base, Random& rng) {
    double kx[3], ky[3], phase[3];
    for (int i = 0; i < 3; ++i) {
        kx[i] = 2 * M_PI / rng.uniform(1.5, 4.0);
        ky[i] = 2 * M_PI / rng.uniform(1.5, 4.0);
        phase[i] = rng.uniform(0, 2 * M_PI);
    }
    for (int y = 0; y < img.rows; ++y) {
        auto* row = img.ptr<cv::Vec3b>(y);
        for (int x = 0; x < img.cols; ++x) {
            double d = 0;
            for (int i = 0; i < 3; ++i) d += std::sin(kx[i] * x / pxm + ky[i] * y / pxm + phase[i]);
            const double f = 1.0 + 0.012 * d;
            for (int c = 0; c < 3; ++c) row[x][c] = cv::saturate_cast<uchar>(base[c] * f);
        }
    }
}
}  // namespace

SurfaceSpec SurfaceSpec::parse(const std::string& text) {
    SurfaceSpec s;
    if (text == "posters") {
        s.style = SurfaceStyle::Posters;
        s.baseColor = {170, 180, 190};
    } else if (text == "bricks") {
        s.style = SurfaceStyle::Bricks;
    } else if (text == "plain") {
        s.style = SurfaceStyle::Plain;
    } else if (text == "tiles") {
        s.style = SurfaceStyle::Tiles;
        s.baseColor = {150, 165, 175};
    } else if (text.rfind("image:", 0) == 0) {
        const auto last = text.rfind(':');
        s.style = SurfaceStyle::Image;
        s.imagePath = text.substr(6, last - 6);
        try {
            s.imageWidth = std::stod(text.substr(last + 1));
        } catch (const std::exception&) {
            s.imageWidth = 0;
        }
        if (last <= 6 || s.imageWidth <= 0) {
            throw std::invalid_argument("surface '" + text + "': expected image:<path>:<width m>");
        }
    } else {
        throw std::invalid_argument("unknown surface '" + text +
                                    "' (posters, bricks, plain, tiles, image:<path>:<width m>)");
    }
    return s;
}

SurfaceTexture SurfaceTexture::generate(const SurfaceSpec& spec, double width, double height,
                                        double pixelsPerMetre, Random& rng) {
    SurfaceTexture t;
    t.px_per_m_ = pixelsPerMetre;
    const int cols = std::max(2, static_cast<int>(std::ceil(width * pixelsPerMetre)));
    const int rows = std::max(2, static_cast<int>(std::ceil(height * pixelsPerMetre)));
    t.raster_.create(rows, cols);
    t.raster_.setTo(cv::Scalar(spec.baseColor[0], spec.baseColor[1], spec.baseColor[2]));
    switch (spec.style) {
        case SurfaceStyle::Posters:
            drawPosters(t.raster_, pixelsPerMetre, rng);
            break;
        case SurfaceStyle::Bricks:
            drawBricks(t.raster_, pixelsPerMetre, rng);
            break;
        case SurfaceStyle::Tiles:
            drawTiles(t.raster_, pixelsPerMetre, spec.baseColor, rng);
            break;
        case SurfaceStyle::Plain:
            drawPlain(t.raster_, pixelsPerMetre, spec.baseColor, rng);
            break;
        case SurfaceStyle::Image: {
            const cv::Mat photo = cv::imread(spec.imagePath, cv::IMREAD_COLOR);
            if (photo.empty()) throw std::runtime_error(spec.imagePath + ": cannot read image");
            const int tileW = std::max(2, static_cast<int>(spec.imageWidth * pixelsPerMetre));
            const int tileH = std::max(2, tileW * photo.rows / photo.cols);
            cv::Mat tile;
            cv::resize(photo, tile, cv::Size(tileW, tileH), 0, 0, cv::INTER_AREA);
            for (int y = 0; y < rows; y += tileH) {
                for (int x = 0; x < cols; x += tileW) {
                    const cv::Rect dst(x, y, std::min(tileW, cols - x), std::min(tileH, rows - y));
                    tile(cv::Rect(0, 0, dst.width, dst.height)).copyTo(t.raster_(dst));
                }
            }
        } break;
    }
    // Image rows grow downwards; v grows upwards: flip so that row 0 is v = 0 (the floor).
    cv::flip(t.raster_, t.raster_, 0);
    return t;
}

void SurfaceTexture::bakeShading(const std::function<double(double u, double v)>& shade) {
    for (int y = 0; y < raster_.rows; ++y) {
        auto* row = raster_.ptr<cv::Vec3b>(y);
        const double v = (y + 0.5) / px_per_m_;
        for (int x = 0; x < raster_.cols; ++x) {
            const double f = shade((x + 0.5) / px_per_m_, v);
            for (int c = 0; c < 3; ++c) row[x][c] = cv::saturate_cast<uchar>(row[x][c] * f);
        }
    }
    if (!integral_.empty()) prepareAreaSampling();  // (the raster changed)
}

void SurfaceTexture::prepareAreaSampling() {
    // 32-bit sums are exact up to 8.4 million texels (255 each): 210 m^2 of wall at 200 px/m.
    if (static_cast<double>(raster_.total()) * 255 < 2147483647.0) {
        cv::integral(raster_, integral_, CV_32S);
    } else {
        cv::integral(raster_, integral_, CV_64F);
    }
}

cv::Vec3d SurfaceTexture::integralAt(double x, double y) const {
    const int x0 = std::min(static_cast<int>(x), raster_.cols - 1);
    const int y0 = std::min(static_cast<int>(y), raster_.rows - 1);
    const double ax = x - x0, ay = y - y0;
    const double w00 = (1 - ax) * (1 - ay), w01 = ax * (1 - ay), w10 = (1 - ax) * ay, w11 = ax * ay;
    cv::Vec3d out;
    const auto blend = [&](const auto* r0, const auto* r1) {
        for (int c = 0; c < 3; ++c)
            out[c] = w00 * r0[c] + w01 * r0[3 + c] + w10 * r1[c] + w11 * r1[3 + c];
    };
    if (integral_.depth() == CV_32S) {
        blend(integral_.ptr<int>(y0) + 3 * x0, integral_.ptr<int>(y0 + 1) + 3 * x0);
    } else {
        blend(integral_.ptr<double>(y0) + 3 * x0, integral_.ptr<double>(y0 + 1) + 3 * x0);
    }
    return out;
}

cv::Vec3f SurfaceTexture::sampleArea(double u, double v, double du, double dv) const {
    if (integral_.empty())
        throw std::logic_error("SurfaceTexture::sampleArea before prepareAreaSampling");
    // Magnified (the footprint within one texel both ways): the bilinear sample is the same.
    if (std::abs(du) * px_per_m_ <= 1 && std::abs(dv) * px_per_m_ <= 1) return sample(u, v);
    // In texels, the centre kept where a one-texel box fits (as sample() clamps).
    const double cols = raster_.cols, rows = raster_.rows;
    const double cx = std::clamp(u * px_per_m_, 0.5, cols - 0.5);
    const double cy = std::clamp(v * px_per_m_, 0.5, rows - 0.5);
    const double hx = 0.5 * std::max(1.0, std::abs(du) * px_per_m_);
    const double hy = 0.5 * std::max(1.0, std::abs(dv) * px_per_m_);
    const double x0 = std::max(0.0, cx - hx), x1 = std::min(cols, cx + hx);
    const double y0 = std::max(0.0, cy - hy), y1 = std::min(rows, cy + hy);
    const cv::Vec3d sum =
        integralAt(x1, y1) - integralAt(x0, y1) - integralAt(x1, y0) + integralAt(x0, y0);
    const double area = (x1 - x0) * (y1 - y0);
    return cv::Vec3f(static_cast<float>(sum[0] / area), static_cast<float>(sum[1] / area),
                     static_cast<float>(sum[2] / area));
}

cv::Vec3f SurfaceTexture::sample(double u, double v) const {
    const double fx = std::clamp(u * px_per_m_ - 0.5, 0.0, raster_.cols - 1.001);
    const double fy = std::clamp(v * px_per_m_ - 0.5, 0.0, raster_.rows - 1.001);
    const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
    const float ax = static_cast<float>(fx - x0), ay = static_cast<float>(fy - y0);
    const auto* r0 = raster_.ptr<cv::Vec3b>(y0) + x0;
    const auto* r1 = raster_.ptr<cv::Vec3b>(y0 + 1) + x0;
    cv::Vec3f out;
    for (int c = 0; c < 3; ++c) {
        const float top = r0[0][c] + ax * (r0[1][c] - r0[0][c]);
        const float bottom = r1[0][c] + ax * (r1[1][c] - r1[0][c]);
        out[c] = top + ay * (bottom - top);
    }
    return out;
}

}  // namespace lodestone::sim
