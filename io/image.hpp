#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "casmap/core/grid.hpp"

namespace casmap::io {

/// Reads a single-channel 32-bit float TIFF (metres, or certainty counts). Image row = map row
/// (along-track), image column = map col. Throws InputError naming the file and the rule for
/// a missing or unreadable file, a non-TIFF, an 8/16-bit or a multi-channel image.
/// The image size the TIFF header declares is checked against core/limits.hpp before decoding.
[[nodiscard]] core::MapF ReadMapTiff(const std::filesystem::path& path);

/// ReadMapTiff on the bytes of a TIFF file already in memory; `name` names it in messages.
[[nodiscard]] core::MapF DecodeMapTiff(std::string_view bytes, const std::string& name);

/// Writes `map` as a single-channel 32-bit float TIFF, atomically (temporary file + rename).
void WriteMapTiff(const std::filesystem::path& path, const core::MapF& map);

/// Colour PNG of a map for people: a colour scale with a legend bar (values in `unit`);
/// NaN cells drawn magenta, `unknown` cells (mask != 0, e.g. certainty 0) drawn dark grey.
struct PngStyle {
    std::optional<float> min;  // colour scale limits; default: finite min/max of the map
    std::optional<float> max;
    std::string title;  // drawn above the legend
    std::string unit = "m";
    const core::Raster<std::uint8_t>* unknown = nullptr;  // optional mask, same size
    int pixels_per_cell = 0;                              // 0: chosen so the map is about 600 px
};
void WriteMapPng(const std::filesystem::path& path, const core::MapF& map, const PngStyle& style);

/// Colour PNG of a class raster with a legend: one (name, BGR colour) per class value.
struct ClassLegendEntry {
    std::string name;
    unsigned char b = 0, g = 0, r = 0;
};
void WriteClassesPng(const std::filesystem::path& path,
                     const core::Raster<std::uint8_t>& classes,
                     const std::vector<ClassLegendEntry>& legend,
                     const std::string& title);

}  // namespace casmap::io
