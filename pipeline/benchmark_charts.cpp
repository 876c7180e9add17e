// Drawing half of benchmark_report.hpp: the Fig. 8 chart, the Fig. 7 sheets and the sweep heat
// map (OpenCV), each written atomically as PNG.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "casmap/core/input_error.hpp"
#include "casmap/io/atomic_file.hpp"
#include "casmap/pipeline/benchmark_report.hpp"

namespace casmap::pipeline {
namespace {
namespace fs = std::filesystem;

const cv::Scalar kBlack(0, 0, 0);
const cv::Scalar kGrey(160, 160, 160);
const cv::Scalar kUnknown(60, 60, 60);
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

// One colour per filter (BGR), readable on white and by most colour-blind readers
// (Okabe-Ito palette).
cv::Scalar FilterColour(const std::string& name) {
    if (name == "cas") return {0, 0, 0};          // black: the paper's filter
    if (name == "wiener") return {178, 114, 0};   // blue
    if (name == "average") return {0, 159, 230};  // orange
    if (name == "median") return {115, 158, 0};   // bluish green
    return {167, 121, 204};                       // reddish purple: cwm
}

void Text(cv::Mat& img,
          const std::string& s,
          cv::Point at,
          double scale = 0.45,
          cv::Scalar colour = kBlack) {
    cv::putText(img, s, at, kFont, scale, colour, 1, cv::LINE_AA);
}

int TextWidth(const std::string& s, double scale = 0.45) {
    int baseline = 0;
    return cv::getTextSize(s, kFont, scale, 1, &baseline).width;
}

void WritePng(const fs::path& path, const cv::Mat& image) {
    std::vector<uchar> bytes;
    if (!cv::imencode(".png", image, bytes, {cv::IMWRITE_PNG_COMPRESSION, 6})) {
        throw MakeInputError(path.string(), "image", "", "OpenCV cannot encode PNG");
    }
    io::WriteAtomically(path, [&](const fs::path& tmp) {
        std::ofstream out(tmp, std::ios::binary);
        out.write(reinterpret_cast<const char*>(bytes.data()),
                  static_cast<std::streamsize>(bytes.size()));
        out.close();
        if (!out) {
            throw MakeInputError(path.string(), "output path", "", "write failed");
        }
    });
}

std::string Fixed(double v, int decimals) {
    if (!std::isfinite(v)) {
        return "-";
    }
    char buf[64];
    std::snprintf(buf, sizeof(buf), "%.*f", decimals, v);
    return buf;
}

/// OpenCV's viridis colour map at u in [0, 1] (a 256-entry table built once).
/// Axis labels: up to 6 significant digits, no trailing zeros.
std::string Short(double v) {
    char buf[64];
    std::snprintf(buf, sizeof(buf), "%.6g", v);
    return buf;
}

cv::Vec3b Viridis(double u) {
    static const std::array<cv::Vec3b, 256> table = [] {
        cv::Mat ramp(1, 256, CV_8U);
        for (int i = 0; i < 256; ++i) {
            ramp.at<uchar>(0, i) = static_cast<uchar>(i);
        }
        cv::Mat colours;
        cv::applyColorMap(ramp, colours, cv::COLORMAP_VIRIDIS);
        std::array<cv::Vec3b, 256> t{};
        for (int i = 0; i < 256; ++i) {
            t[static_cast<std::size_t>(i)] = colours.at<cv::Vec3b>(0, i);
        }
        return t;
    }();
    const double v = std::isfinite(u) ? std::clamp(u, 0.0, 1.0) : 0.0;
    return table[static_cast<std::size_t>(std::lround(v * 255.0))];
}

/// "Nice" axis maximum: 1, 2 or 5 times a power of ten at or above v.
double NiceCeil(double v) {
    if (!(v > 0.0)) {
        return 1.0;
    }
    const double p = std::pow(10.0, std::floor(std::log10(v)));
    for (const double m : {1.0, 2.0, 2.5, 5.0, 10.0}) {
        if (m * p >= v * (1.0 - 1e-12)) {
            return m * p;
        }
    }
    return 10.0 * p;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Fig. 8-style chart

namespace {

void DrawPanel(cv::Mat& img,
               const cv::Rect& box,
               const std::string& test,
               const std::vector<const BenchRun*>& runs,
               double y_max) {
    const int left = box.x + 55;
    const int right = box.x + box.width - 15;
    const int top = box.y + 30;
    const int bottom = box.y + box.height - 40;
    Text(img, "test " + test, {box.x + box.width / 2 - 25, box.y + 20}, 0.55);
    cv::rectangle(img, {left, top}, {right, bottom}, kBlack, 1);
    std::vector<int> courses;
    for (const BenchRun* r : runs) {
        courses.push_back(r->course);
    }
    const std::size_t n = courses.size();
    const auto x_of = [&](std::size_t i) {
        return left + static_cast<int>((static_cast<double>(i) + 0.5) * (right - left) /
                                       static_cast<double>(std::max<std::size_t>(n, 1)));
    };
    const auto y_of = [&](double v) {
        const double u = std::clamp(v / y_max, 0.0, 1.0);
        return bottom - static_cast<int>(std::lround(u * (bottom - top)));
    };
    for (int k = 0; k <= 4; ++k) {
        const double v = y_max * k / 4.0;
        const int y = y_of(v);
        cv::line(img, {left, y}, {right, y}, cv::Scalar(225, 225, 225), 1);
        const std::string label = Fixed(v, y_max < 0.1 ? 3 : 2);
        Text(img, label, {left - 8 - TextWidth(label, 0.4), y + 4}, 0.4);
    }
    cv::rectangle(img, {left, top}, {right, bottom}, kBlack, 1);
    for (std::size_t i = 0; i < n; ++i) {
        const std::string label = std::to_string(courses[i]);
        Text(img, label, {x_of(i) - TextWidth(label, 0.4) / 2, bottom + 16}, 0.4);
    }
    Text(img, "obstacle course", {(left + right) / 2 - 55, bottom + 34}, 0.45);
    Text(img, "PI", {box.x + 8, top - 8}, 0.5);
    for (const std::string& name : BenchFilterNames()) {
        const cv::Scalar colour = FilterColour(name);
        cv::Point prev(-1, -1);
        for (std::size_t i = 0; i < n; ++i) {
            const auto found = runs[i]->filters.find(name);
            const double pi = found != runs[i]->filters.end() ? found->second.pi : std::nan("");
            if (!std::isfinite(pi)) {
                prev = {-1, -1};
                continue;
            }
            const cv::Point p(x_of(i), y_of(pi));
            if (prev.x >= 0) {
                cv::line(img, prev, p, colour, name == "cas" ? 2 : 1, cv::LINE_AA);
            }
            if (pi > y_max) {  // off the scale: an upward arrow at the top
                cv::arrowedLine(img, {p.x, top + 14}, {p.x, top + 2}, colour, 1, cv::LINE_AA);
            } else {
                cv::circle(img, p, 3, colour, -1, cv::LINE_AA);
            }
            prev = p;
        }
    }
}

}  // namespace

void WritePiChart(const fs::path& path, const std::vector<BenchRun>& runs) {
    std::vector<std::string> tests;
    for (const char* t : {"T", "TR", "TP", "TRP"}) {
        if (std::any_of(runs.begin(), runs.end(),
                        [&](const BenchRun& r) { return r.test == t && r.scene.empty(); })) {
            tests.push_back(t);
        }
    }
    // One y scale for every panel: the largest PI below 2 (a filter doubling the error is off
    // the scale and drawn as an arrow).
    double y_max = 0.0;
    for (const BenchRun& r : runs) {
        for (const std::string& name : BenchFilterNames()) {
            const auto f = r.filters.find(name);
            if (f != r.filters.end() && std::isfinite(f->second.pi) && f->second.pi <= 2.0) {
                y_max = std::max(y_max, f->second.pi);
            }
        }
    }
    y_max = NiceCeil(y_max);
    const int panel_w = 620;
    const int panel_h = 300;
    const int cols = tests.size() > 1 ? 2 : 1;
    const int rows = static_cast<int>((tests.size() + 1) / 2);
    cv::Mat img(std::max(rows, 1) * panel_h + 70, cols * panel_w, CV_8UC3,
                cv::Scalar(255, 255, 255));
    Text(img, "Filter performance index per obstacle course (Eq. 11; lower is better)", {10, 22},
         0.6);
    int lx = 10;
    for (const std::string& name : BenchFilterNames()) {
        cv::line(img, {lx, 45}, {lx + 25, 45}, FilterColour(name), name == "cas" ? 2 : 1);
        cv::circle(img, {lx + 12, 45}, 3, FilterColour(name), -1, cv::LINE_AA);
        Text(img, FilterDisplayName(name), {lx + 30, 50});
        lx += 40 + TextWidth(FilterDisplayName(name)) + 25;
    }
    for (std::size_t k = 0; k < tests.size(); ++k) {
        std::vector<const BenchRun*> sel;
        for (const BenchRun& r : runs) {
            if (r.test == tests[k] && r.scene.empty()) {
                sel.push_back(&r);
            }
        }
        const cv::Rect box(static_cast<int>(k % 2) * panel_w,
                           70 + static_cast<int>(k / 2) * panel_h, panel_w, panel_h);
        DrawPanel(img, box, tests[k], sel, y_max);
    }
    WritePng(path, img);
}

// ---------------------------------------------------------------------------------------------
// Fig. 7-style sheet

void WriteSheet(const fs::path& path, const SheetMaps& maps, const std::string& title) {
    // One colour scale from the ground truth: datum to the tallest object. Values beyond it
    // are clamped (marked by the legend's arrows).
    float lo = 0.0F;
    float hi = 0.0F;
    for (const float v : maps.truth.data) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    if (!(hi > lo)) {
        hi = lo + 1.0F;
    }
    std::vector<std::pair<std::string, const core::MapF*>> panels = {{"raw", &maps.raw},
                                                                     {"ground truth", &maps.truth}};
    for (const std::string& name : BenchFilterNames()) {
        const auto it = maps.filtered.find(name);
        if (it != maps.filtered.end()) {
            panels.emplace_back(FilterDisplayName(name), &it->second);
        }
    }
    const int rows = maps.truth.rows;
    const int cols = maps.truth.cols;
    const int ppc = std::max(1, std::min(3, 480 / std::max(rows, 1)));
    const int pw = cols * ppc;
    const int ph = rows * ppc;
    const int gap = 12;
    const int top = 58;
    const int legend_w = 190;
    cv::Mat img(top + ph + 40, static_cast<int>(panels.size()) * (pw + gap) + gap + legend_w,
                CV_8UC3, cv::Scalar(255, 255, 255));
    Text(img, title, {gap, 22}, 0.6);
    for (std::size_t k = 0; k < panels.size(); ++k) {
        const core::MapF& m = *panels[k].second;
        const int x0 = gap + static_cast<int>(k) * (pw + gap);
        Text(img, panels[k].first, {x0 + pw / 2 - TextWidth(panels[k].first) / 2, top - 8});
        for (int r = 0; r < rows; ++r) {
            for (int c = 0; c < cols; ++c) {
                const float v = m.at(r, c);
                cv::Vec3b colour = Viridis((v - lo) / (hi - lo));
                if (!std::isfinite(v)) {
                    colour = cv::Vec3b(255, 0, 255);
                } else if (k == 0 && maps.certainty.at(r, c) == 0.0F) {
                    colour = cv::Vec3b(60, 60, 60);  // raw map: never observed
                }
                cv::rectangle(img, cv::Rect(x0 + c * ppc, top + r * ppc, ppc, ppc),
                              cv::Scalar(colour[0], colour[1], colour[2]), -1);
            }
        }
        cv::rectangle(img, cv::Rect(x0 - 1, top - 1, pw + 2, ph + 2), kGrey, 1);
    }
    // Travel direction: rows run along +x from the top down.
    const int ax = gap;
    cv::arrowedLine(img, {ax + 5, top + ph + 12}, {ax + 5, top + ph + 32}, kBlack, 1, cv::LINE_AA,
                    0, 0.3);
    Text(img, "v: travel (+x, rows); columns: +y", {ax + 14, top + ph + 28}, 0.4);
    // Legend: colour bar, max at the top.
    const int lx = static_cast<int>(panels.size()) * (pw + gap) + gap + 10;
    const int bar_h = std::min(ph, 200);
    for (int y = 0; y < bar_h; ++y) {
        const cv::Vec3b c = Viridis(1.0 - static_cast<double>(y) / (bar_h - 1));
        cv::line(img, {lx, top + y}, {lx + 20, top + y}, cv::Scalar(c[0], c[1], c[2]));
    }
    Text(img, ">= " + Fixed(hi, 3) + " m", {lx + 26, top + 10}, 0.4);
    Text(img, Fixed(0.5 * (lo + hi), 3) + " m", {lx + 26, top + bar_h / 2 + 4}, 0.4);
    Text(img, "<= " + Fixed(lo, 3) + " m", {lx + 26, top + bar_h}, 0.4);
    cv::rectangle(img, cv::Rect(lx, top + bar_h + 14, 20, 12), kUnknown, -1);
    Text(img, "never observed (raw)", {lx + 26, top + bar_h + 25}, 0.4);
    Text(img, "elevation, one scale", {lx, top + bar_h + 50}, 0.4);
    WritePng(path, img);
}

// ---------------------------------------------------------------------------------------------
// Sweep heat map

void WriteHeatMap(const fs::path& path, const HeatMap& map) {
    const int nx = static_cast<int>(map.x_values.size());
    const int ny = static_cast<int>(map.y_values.size());
    const int cw = std::clamp(700 / std::max(nx, 1), 40, 90);
    const int ch = std::clamp(500 / std::max(ny, 1), 24, 60);
    const int left = 90;
    const int top = 50;
    const int width = std::max({left + nx * cw + 150, TextWidth(map.title, 0.55) + 20,
                                TextWidth(map.marked_legend, 0.4) + 20});
    cv::Mat img(top + ny * ch + 70, width, CV_8UC3, cv::Scalar(255, 255, 255));
    Text(img, map.title, {10, 22}, 0.55);
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    for (const double v : map.values) {
        if (std::isfinite(v)) {
            lo = std::min(lo, v);
            hi = std::max(hi, v);
        }
    }
    if (!(hi > lo)) {
        hi = std::isfinite(lo) ? lo + 1e-9 : 1.0;
        lo = std::isfinite(lo) ? lo : 0.0;
    }
    for (int iy = 0; iy < ny; ++iy) {
        for (int ix = 0; ix < nx; ++ix) {
            const double v = map.values[static_cast<std::size_t>(iy * nx + ix)];
            // Row 0 at the bottom so the y axis grows upward.
            const cv::Rect cell(left + ix * cw, top + (ny - 1 - iy) * ch, cw, ch);
            const cv::Vec3b c =
                std::isfinite(v) ? Viridis((v - lo) / (hi - lo)) : cv::Vec3b(200, 200, 200);
            cv::rectangle(img, cell, cv::Scalar(c[0], c[1], c[2]), -1);
            const bool dark = std::isfinite(v) && (v - lo) / (hi - lo) < 0.6;
            const std::size_t at = static_cast<std::size_t>(iy * nx + ix);
            if (at < map.marked.size() && map.marked[at]) {  // a frame inside the cell
                cv::rectangle(img, {cell.x + 2, cell.y + 2, cell.width - 4, cell.height - 4},
                              cv::Scalar(0, 0, 230), 3);
            }
            const std::string label =
                Fixed(v, 3) + (static_cast<int>(at) == map.starred ? "*" : "");
            Text(img, label, {cell.x + cw / 2 - TextWidth(label, 0.38) / 2, cell.y + ch / 2 + 4},
                 0.38, dark ? cv::Scalar(255, 255, 255) : kBlack);
        }
    }
    for (int ix = 0; ix < nx; ++ix) {
        const std::string label = Short(map.x_values[static_cast<std::size_t>(ix)]);
        Text(img, label, {left + ix * cw + cw / 2 - TextWidth(label, 0.38) / 2, top + ny * ch + 16},
             0.38);
    }
    Text(img, map.x_name, {left + nx * cw / 2 - TextWidth(map.x_name) / 2, top + ny * ch + 40});
    if (!map.marked_legend.empty()) {
        Text(img, map.marked_legend, {10, top + ny * ch + 62}, 0.4);
    }
    for (int iy = 0; iy < ny; ++iy) {
        const std::string label = Short(map.y_values[static_cast<std::size_t>(iy)]);
        Text(img, label, {left - 8 - TextWidth(label, 0.38), top + (ny - 1 - iy) * ch + ch / 2 + 4},
             0.38);
    }
    Text(img, map.y_name, {10, top - 10});
    const int lx = left + nx * cw + 20;
    const int bar_h = std::min(ny * ch, 200);
    for (int y = 0; y < bar_h; ++y) {
        const cv::Vec3b c = Viridis(1.0 - static_cast<double>(y) / (bar_h - 1));
        cv::line(img, {lx, top + y}, {lx + 20, top + y}, cv::Scalar(c[0], c[1], c[2]));
    }
    Text(img, Fixed(hi, 3), {lx + 26, top + 10}, 0.4);
    Text(img, Fixed(lo, 3), {lx + 26, top + bar_h}, 0.4);
    Text(img, "mean PI", {lx, top + bar_h + 22}, 0.4);
    WritePng(path, img);
}

}  // namespace casmap::pipeline
