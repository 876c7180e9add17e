#include "casmap/io/image.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string_view>

#include "casmap/core/input_error.hpp"
#include "casmap/core/limits.hpp"
#include "casmap/core/text.hpp"
#include "casmap/io/atomic_file.hpp"

namespace casmap::io {
namespace fs = std::filesystem;
namespace {

const char* const kTiffRule = "must be a single-channel 32-bit float TIFF";

std::string DepthName(int depth) {
    switch (depth) {
        case CV_8U:
            return "8-bit unsigned";
        case CV_8S:
            return "8-bit signed";
        case CV_16U:
            return "16-bit unsigned";
        case CV_16S:
            return "16-bit signed";
        case CV_32S:
            return "32-bit integer";
        case CV_32F:
            return "32-bit float";
        case CV_64F:
            return "64-bit float";
        default:
            return "unknown depth";
    }
}

bool HasTiffMagic(std::string_view b) {
    if (b.size() < 4) {
        return false;
    }
    const bool little = b[0] == 'I' && b[1] == 'I' && (b[2] == 42 || b[2] == 43) && b[3] == 0;
    const bool big = b[0] == 'M' && b[1] == 'M' && b[2] == 0 && (b[3] == 42 || b[3] == 43);
    return little || big;
}

// Reads the first image directory of a TIFF (classic or BigTIFF) for the sizes libtiff will
// allocate: image width x length and tile width x length must stay within the pixel limit.
class TiffHeader {
public:
    TiffHeader(std::string_view bytes, std::string name)
        : b_(bytes), name_(std::move(name)), little_(bytes[0] == 'I') {}

    void CheckSizes() const {
        const bool big = Get(2, 2) == 43;
        const std::uint64_t ifd = big ? Get(8, 8) : Get(4, 4);
        const std::uint64_t count = big ? Get(ifd, 8) : Get(ifd, 2);
        const std::uint64_t entry_bytes = big ? 20 : 12;
        const std::uint64_t first = ifd + (big ? 8 : 2);
        if (count > (b_.size() - std::min<std::uint64_t>(first, b_.size())) / entry_bytes) {
            throw Error("TIFF header: directory entries", count, "more than the file holds");
        }
        std::uint64_t tags[4] = {0, 0, 0, 0};  // width 256, length 257, tile w 322, tile l 323
        bool seen[4] = {false, false, false, false};
        for (std::uint64_t i = 0; i < count; ++i) {
            const std::uint64_t e = first + i * entry_bytes;
            const std::uint64_t tag = Get(e, 2);
            const std::uint64_t type = Get(e + 2, 2);
            const std::uint64_t value_at = e + (big ? 12 : 8);
            const std::uint64_t value = type == 3    ? Get(value_at, 2)
                                        : type == 4  ? Get(value_at, 4)
                                        : type == 16 ? Get(value_at, 8)
                                                     : 0;
            const int slot = tag == 256 ? 0 : tag == 257 ? 1 : tag == 322 ? 2 : tag == 323 ? 3 : -1;
            if (slot >= 0) {
                // A directory lists each tag once; with two, libtiff sizes the image by one and
                // this check would read the other (tiff_map_fuzz, session 8: 65283 x 12090).
                if (seen[slot]) {
                    throw Error("TIFF header: tag", tag, "given twice in the first directory");
                }
                seen[slot] = true;
                tags[slot] = value;
            }
        }
        CheckPixels("TIFF header: width x length", tags[0], tags[1]);
        CheckPixels("TIFF header: tile width x length", tags[2], tags[3]);
    }

private:
    void CheckPixels(const std::string& field, std::uint64_t w, std::uint64_t h) const {
        const std::uint64_t limit = core::limits::kMaxImagePixels;
        if (w > limit || h > limit || w * h > limit) {
            throw MakeInputError(name_, field, std::to_string(w) + " x " + std::to_string(h),
                                 "pixel limit " + std::to_string(limit) + ", see docs/limits.md");
        }
    }
    InputError Error(const std::string& field, std::uint64_t v, const std::string& rule) const {
        return MakeInputError(name_, field, std::to_string(v), rule);
    }
    // An unsigned integer of `n` bytes at `at`, in the file's byte order.
    std::uint64_t Get(std::uint64_t at, std::uint64_t n) const {
        if (at > b_.size() || n > b_.size() - at) {
            throw Error("TIFF header: offset", at, "points beyond the end of the file");
        }
        std::uint64_t v = 0;
        for (std::uint64_t k = 0; k < n; ++k) {
            const std::uint64_t byte =
                static_cast<unsigned char>(b_[at + (little_ ? n - 1 - k : k)]);
            v = (v << 8) | byte;
        }
        return v;
    }

    std::string_view b_;
    std::string name_;
    bool little_;
};

void WriteBytesAtomically(const fs::path& path, const std::vector<uchar>& bytes) {
    WriteAtomically(path, [&](const fs::path& tmp) {
        std::ofstream out(tmp, std::ios::binary);
        out.write(reinterpret_cast<const char*>(bytes.data()),
                  static_cast<std::streamsize>(bytes.size()));
        out.close();
        if (!out) {
            throw MakeInputError(path.string(), "output path", "", "write failed");
        }
    });
}

void Encode(const fs::path& path, const std::string& ext, const cv::Mat& image) {
    std::vector<uchar> bytes;
    if (!cv::imencode(ext, image, bytes)) {
        throw MakeInputError(path.string(), "image", "", "OpenCV cannot encode " + ext);
    }
    WriteBytesAtomically(path, bytes);
}

std::string Format(double v, const std::string& unit) {
    return core::FormatNumber(v, 3) + " " + unit;
}

int PixelsPerCell(int requested, int rows, int cols) {
    if (requested > 0) {
        return requested;
    }
    return std::max(1, 600 / std::max(1, std::max(rows, cols)));
}

// Map image on the left, a legend panel on the right, a title line on top.
cv::Mat Compose(const cv::Mat& map_bgr, const std::string& title, int legend_width) {
    const int top = 30;
    const int height = std::max(map_bgr.rows + top + 10, 260);
    cv::Mat canvas(height, map_bgr.cols + legend_width + 20, CV_8UC3, cv::Scalar(255, 255, 255));
    map_bgr.copyTo(canvas(cv::Rect(10, top, map_bgr.cols, map_bgr.rows)));
    cv::putText(canvas, title, cv::Point(10, 20), cv::FONT_HERSHEY_SIMPLEX, 0.5,
                cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    return canvas;
}

}  // namespace

core::MapF DecodeMapTiff(std::string_view bytes, const std::string& name) {
    core::limits::CheckLimit(name, "file size (bytes)", bytes.size(), core::limits::kMaxFileBytes,
                             "TIFF file");
    if (!HasTiffMagic(bytes)) {
        throw MakeInputError(name, "format", "", std::string(kTiffRule) + " (not a TIFF file)");
    }
    TiffHeader(bytes, name).CheckSizes();
    cv::Mat image;
    try {
        const cv::Mat buffer(1, static_cast<int>(bytes.size()), CV_8U,
                             const_cast<char*>(bytes.data()));
        image = cv::imdecode(buffer, cv::IMREAD_UNCHANGED);
    } catch (const cv::Exception& e) {
        throw MakeInputError(name, "format", "",
                             std::string(kTiffRule) + " (OpenCV: " + e.err.substr(0, 80) + ")");
    }
    if (image.empty()) {
        throw MakeInputError(name, "format", "",
                             std::string(kTiffRule) + " (OpenCV cannot decode it)");
    }
    if (image.channels() != 1) {
        throw MakeInputError(name, "channels", std::to_string(image.channels()), kTiffRule);
    }
    if (image.depth() != CV_32F) {
        throw MakeInputError(name, "sample format", DepthName(image.depth()), kTiffRule);
    }
    core::MapF map(image.rows, image.cols);
    for (int i = 0; i < image.rows; ++i) {
        const float* src = image.ptr<float>(i);
        std::copy(src, src + image.cols, &map.at(i, 0));
    }
    return map;
}

core::MapF ReadMapTiff(const fs::path& path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) {
        throw MakeInputError(path.string(), "file", "", "does not exist or is not a file");
    }
    core::limits::CheckLimit(path.string(), "file size (bytes)", fs::file_size(path, ec),
                             core::limits::kMaxFileBytes, "TIFF file");
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.is_open()) {
        throw MakeInputError(path.string(), "file", "", "cannot be read");
    }
    return DecodeMapTiff(bytes, path.string());
}

void WriteMapTiff(const fs::path& path, const core::MapF& map) {
    if (map.rows <= 0 || map.cols <= 0) {
        throw MakeInputError(path.string(), "map", "empty", "cannot write an empty map");
    }
    const cv::Mat view(map.rows, map.cols, CV_32F, const_cast<float*>(map.data.data()));
    Encode(path, ".tiff", view);
}

void WriteMapPng(const fs::path& path, const core::MapF& map, const PngStyle& style) {
    if (map.rows <= 0 || map.cols <= 0) {
        throw MakeInputError(path.string(), "map", "empty", "cannot draw an empty map");
    }
    float lo = std::numeric_limits<float>::infinity();
    float hi = -std::numeric_limits<float>::infinity();
    for (const float v : map.data) {
        if (std::isfinite(v)) {
            lo = std::min(lo, v);
            hi = std::max(hi, v);
        }
    }
    lo = style.min.value_or(std::isfinite(lo) ? lo : 0.0F);
    hi = style.max.value_or(std::isfinite(hi) ? hi : 1.0F);
    const float span = hi > lo ? hi - lo : 1.0F;
    cv::Mat gray(map.rows, map.cols, CV_8U);
    for (int i = 0; i < map.rows; ++i) {
        for (int j = 0; j < map.cols; ++j) {
            const float v = map.at(i, j);
            const float u = std::isfinite(v) ? std::clamp((v - lo) / span, 0.0F, 1.0F) : 0.0F;
            gray.at<uchar>(i, j) = static_cast<uchar>(std::lround(u * 255.0F));
        }
    }
    cv::Mat bgr;
    cv::applyColorMap(gray, bgr, cv::COLORMAP_VIRIDIS);
    const bool have_mask = style.unknown != nullptr && style.unknown->rows == map.rows &&
                           style.unknown->cols == map.cols;
    for (int i = 0; i < map.rows; ++i) {
        for (int j = 0; j < map.cols; ++j) {
            if (!std::isfinite(map.at(i, j))) {
                bgr.at<cv::Vec3b>(i, j) = cv::Vec3b(255, 0, 255);  // NaN: magenta
            } else if (have_mask && style.unknown->at(i, j) != 0) {
                bgr.at<cv::Vec3b>(i, j) = cv::Vec3b(60, 60, 60);  // unknown: dark grey
            }
        }
    }
    const int ppc = PixelsPerCell(style.pixels_per_cell, map.rows, map.cols);
    cv::Mat big;
    cv::resize(bgr, big, cv::Size(), ppc, ppc, cv::INTER_NEAREST);
    const int legend_w = 150;
    cv::Mat canvas = Compose(big, style.title, legend_w);
    // Legend: a vertical colour bar, max at the top, with three labels and the special colours.
    const int x = big.cols + 25;
    const int bar_h = 150;
    for (int y = 0; y < bar_h; ++y) {
        cv::Mat one(1, 1, CV_8U, cv::Scalar(255 - y * 255 / (bar_h - 1)));
        cv::Mat c;
        cv::applyColorMap(one, c, cv::COLORMAP_VIRIDIS);
        cv::line(canvas, cv::Point(x, 30 + y), cv::Point(x + 20, 30 + y), c.at<cv::Vec3b>(0, 0));
    }
    const auto text = [&](const std::string& s, int y) {
        cv::putText(canvas, s, cv::Point(x + 26, y), cv::FONT_HERSHEY_SIMPLEX, 0.4,
                    cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    };
    text(Format(hi, style.unit), 38);
    text(Format(0.5 * (lo + hi), style.unit), 30 + bar_h / 2 + 4);
    text(Format(lo, style.unit), 30 + bar_h);
    cv::rectangle(canvas, cv::Rect(x, 30 + bar_h + 15, 20, 12), cv::Scalar(60, 60, 60), -1);
    text("unknown", 30 + bar_h + 26);
    cv::rectangle(canvas, cv::Rect(x, 30 + bar_h + 35, 20, 12), cv::Scalar(255, 0, 255), -1);
    text("NaN", 30 + bar_h + 46);
    Encode(path, ".png", canvas);
}

void WriteClassesPng(const fs::path& path,
                     const core::Raster<std::uint8_t>& classes,
                     const std::vector<ClassLegendEntry>& legend,
                     const std::string& title) {
    if (classes.rows <= 0 || classes.cols <= 0) {
        throw MakeInputError(path.string(), "classes", "empty", "cannot draw an empty map");
    }
    cv::Mat bgr(classes.rows, classes.cols, CV_8UC3, cv::Scalar(255, 0, 255));
    for (int i = 0; i < classes.rows; ++i) {
        for (int j = 0; j < classes.cols; ++j) {
            const std::uint8_t v = classes.at(i, j);
            if (v < legend.size()) {
                bgr.at<cv::Vec3b>(i, j) = cv::Vec3b(legend[v].b, legend[v].g, legend[v].r);
            }
        }
    }
    const int ppc = PixelsPerCell(0, classes.rows, classes.cols);
    cv::Mat big;
    cv::resize(bgr, big, cv::Size(), ppc, ppc, cv::INTER_NEAREST);
    cv::Mat canvas = Compose(big, title, 150);
    const int x = big.cols + 25;
    for (std::size_t n = 0; n < legend.size(); ++n) {
        const int y = 30 + static_cast<int>(n) * 20;
        cv::rectangle(canvas, cv::Rect(x, y, 20, 12),
                      cv::Scalar(legend[n].b, legend[n].g, legend[n].r), -1);
        cv::putText(canvas, legend[n].name, cv::Point(x + 26, y + 11), cv::FONT_HERSHEY_SIMPLEX,
                    0.4, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    }
    Encode(path, ".png", canvas);
}

}  // namespace casmap::io
