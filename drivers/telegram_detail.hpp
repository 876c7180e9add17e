#pragma once

// Byte helpers shared by telegram.cpp and telegram_parse.cpp (not part of the public API).

#include <cstdint>
#include <cstdio>
#include <span>
#include <string>
#include <vector>

namespace casmap::drivers::detail {

inline std::string Hex(unsigned value, int digits = 2) {
    char buf[16];
    std::snprintf(buf, sizeof(buf), "0x%0*X", digits, value);
    return buf;
}

inline void PutU16(std::vector<std::uint8_t>& out, std::uint16_t v) {
    out.push_back(static_cast<std::uint8_t>(v & 0xFFU));
    out.push_back(static_cast<std::uint8_t>(v >> 8U));
}

inline std::uint16_t GetU16(std::span<const std::uint8_t> bytes, std::size_t at) {
    return static_cast<std::uint16_t>(bytes[at] | (bytes[at + 1] << 8U));
}

}  // namespace casmap::drivers::detail
