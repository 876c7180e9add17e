#include "casmap/pipeline/dataset_card.hpp"

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "casmap/io/atomic_file.hpp"
#include "casmap/io/run_file.hpp"
#include "casmap/pipeline/map_run.hpp"

namespace casmap::pipeline {
namespace {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

constexpr int kSheetSamples = 4;
constexpr int kPixelsPerCell = 3;
constexpr float kLowM = -0.3F;  // colour scale of every tile (m)
constexpr float kHighM = 0.6F;

// A map as a colour tile on one fixed scale; unknown cells (certainty 0) dark grey.
cv::Mat Tile(const core::MapF& map, const core::MapF* certainty, const std::string& title) {
    cv::Mat grey(map.rows, map.cols, CV_8UC1);
    for (int r = 0; r < map.rows; ++r) {
        for (int c = 0; c < map.cols; ++c) {
            const float v = std::isfinite(map.at(r, c)) ? map.at(r, c) : kLowM;
            const float t = std::clamp((v - kLowM) / (kHighM - kLowM), 0.0F, 1.0F);
            grey.at<std::uint8_t>(r, c) = static_cast<std::uint8_t>(std::lround(255.0F * t));
        }
    }
    cv::Mat colour;
    cv::applyColorMap(grey, colour, cv::COLORMAP_VIRIDIS);
    if (certainty != nullptr) {
        for (int r = 0; r < map.rows; ++r) {
            for (int c = 0; c < map.cols; ++c) {
                if (certainty->at(r, c) == 0.0F) {
                    colour.at<cv::Vec3b>(r, c) = cv::Vec3b(60, 60, 60);
                }
            }
        }
    }
    cv::Mat big;
    cv::resize(colour, big, cv::Size(), kPixelsPerCell, kPixelsPerCell, cv::INTER_NEAREST);
    cv::Mat framed(big.rows + 20, big.cols + 8, CV_8UC3, cv::Scalar(255, 255, 255));
    big.copyTo(framed(cv::Rect(4, 20, big.cols, big.rows)));
    cv::putText(framed, title, cv::Point(4, 14), cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(0, 0, 0),
                1, cv::LINE_AA);
    return framed;
}

void WriteContactSheet(const fs::path& out_dir, const std::vector<SampleRecord>& ok) {
    std::vector<cv::Mat> rows;
    for (std::size_t k = 0; k < ok.size() && k < static_cast<std::size_t>(kSheetSamples); ++k) {
        const Json line = Json::parse(ok[k].line);
        const io::RunMaps maps =
            io::ReadRunMaps(out_dir / line["dir"].get<std::string>() / "run.h5");
        if (!maps.truth_m || !maps.elevation_m || !maps.certainty) {
            continue;
        }
        const std::string id = "#" + std::to_string(ok[k].index) + " ";
        std::vector<cv::Mat> tiles = {Tile(*maps.truth_m, nullptr, id + "truth"),
                                      Tile(*maps.elevation_m, &*maps.certainty, id + "raw")};
        if (const auto cas = maps.filtered.find("cas"); cas != maps.filtered.end()) {
            tiles.push_back(Tile(cas->second, nullptr, id + "CAS"));
        }
        cv::Mat row;
        cv::hconcat(tiles, row);
        rows.push_back(row);
    }
    if (rows.empty()) {
        return;
    }
    int width = 0;
    for (const cv::Mat& r : rows) {
        width = std::max(width, r.cols);
    }
    for (cv::Mat& r : rows) {
        cv::copyMakeBorder(r, r, 0, 0, 0, width - r.cols, cv::BORDER_CONSTANT,
                           cv::Scalar(255, 255, 255));
    }
    cv::Mat sheet;
    cv::vconcat(rows, sheet);
    io::EnsureDirectory(out_dir / "card");
    std::vector<std::uint8_t> png;
    cv::imencode(".png", sheet, png);
    io::WriteTextAtomically(out_dir / "card" / "contact_sheet.png",
                            std::string(png.begin(), png.end()));
}

std::string Percent(double part, double whole) {
    return whole > 0.0 ? FormatNumber(std::round(1000.0 * part / whole) / 10.0) + " %" : "-";
}

// One "| key | count | share |" table of string-keyed counts.
std::string CountTable(const std::string& what, const std::map<std::string, double>& counts) {
    double total = 0.0;
    for (const auto& [k, v] : counts) {
        total += v;
    }
    std::string md = "| " + what + " | count | share |\n|---|---:|---:|\n";
    for (const auto& [k, v] : counts) {
        md += "| " + k + " | " + FormatNumber(v) + " | " + Percent(v, total) + " |\n";
    }
    return md + "\n";
}

}  // namespace

void WriteDatasetCard(const scenegen::DatasetSpec& spec,
                      const fs::path& out_dir,
                      const std::vector<SampleRecord>& ok) {
    std::map<std::string, double> splits, scenes, motions, resolutions, labels;
    std::map<std::string, double> pi_sum;
    std::map<std::string, double> pi_n;
    for (const SampleRecord& r : ok) {
        const Json line = Json::parse(r.line);
        ++splits[line["split"].get<std::string>()];
        ++scenes[line["scene"]["type"].get<std::string>()];
        ++motions[line["rig"]["motion"].get<std::string>()];
        ++resolutions[FormatNumber(line["sensor"]["angular_resolution_deg"].get<double>()) +
                      " deg"];
        for (const auto& [k, v] : line["labels"].items()) {
            labels[k] += v.get<double>();
        }
        for (const auto& [k, v] : line["pi"].items()) {
            if (v.is_number()) {
                pi_sum[k] += v.get<double>();
                ++pi_n[k];
            }
        }
    }
    std::string md = "# Data card: " + spec.name + "\n\n";
    md += "casmap " + std::string(CASMAP_VERSION) + ", dataset seed " + std::to_string(spec.seed) +
          ", " + std::to_string(spec.count) + " samples, " + std::to_string(ok.size()) +
          " generated successfully (`manifest.jsonl` lists every "
          "sample, its drawn values, label counts, PI per filter and file hashes; "
          "`dataset.yaml` holds the effective spec).\n\n";
    md +=
        "## What varies\n\nEach sample draws, from its own seed (SplitMix64 of the dataset "
        "seed and its index): a procedural scene (flat obstacle course or fractal terrain "
        "with bumps and ruts; boxes, drums, poles, ramps, curbs, steps, rocks; holes and "
        "ditches below the datum; dark, normal and bright materials), the rig (table motion "
        "T/TR/TP/TRP or the vehicle; speed, mount height and pitch, lateral offset, roll and "
        "pitch profiles), the LMS 200 settings (angular resolution, range mode, noise, beam "
        "divergence, echo width, spike and dropout rates) and an optional pose-estimate "
        "error. The ranges are in `dataset.yaml`.\n\n";
    md += "## Statistics (successful samples)\n\n";
    md += CountTable("split", splits) + CountTable("scene", scenes) +
          CountTable("motion", motions) + CountTable("angular resolution", resolutions);
    md += CountTable("beam label", labels);
    md += "| filter | mean PI (Eq. 11) |\n|---|---:|\n";
    for (const auto& [k, v] : pi_sum) {
        md += "| " + k + " | " + FormatNumber(std::round(1000.0 * v / pi_n[k]) / 1000.0) + " |\n";
    }
    md +=
        "\n## Contact sheet\n\nTruth, raw elevation (grey: unobserved) and CAS-filtered maps of "
        "the first samples, colour scale -0.3 m (dark) to 0.6 m (yellow):\n\n"
        "![contact sheet](card/contact_sheet.png)\n";
    WriteContactSheet(out_dir, ok);
    io::WriteTextAtomically(out_dir / "card.md", md);
}

}  // namespace casmap::pipeline
