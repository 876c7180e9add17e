#pragma once

// SHA-256 (FIPS 180-4) for the dataset manifest's file hashes: small, dependency-free.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace casmap::pipeline {

class Sha256 {
public:
    Sha256();
    void Update(const void* data, std::size_t size);
    /// The digest as 64 lowercase hex digits; the object must not be updated afterwards.
    [[nodiscard]] std::string HexDigest();

private:
    void Block(const std::uint8_t* block);
    std::uint32_t h_[8];
    std::uint8_t buffer_[64] = {};
    std::size_t buffered_ = 0;
    std::uint64_t length_ = 0;
};

/// SHA-256 of a byte string, as hex.
[[nodiscard]] std::string Sha256Hex(std::string_view bytes);
/// SHA-256 of a file's contents, as hex. Throws InputError naming the file if unreadable.
[[nodiscard]] std::string Sha256File(const std::filesystem::path& path);

}  // namespace casmap::pipeline
