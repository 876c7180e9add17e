#pragma once

// A reader of one HDF5 object header message's fields, in order, the way HDF5's decoders advance
// their pointer (io/hdf5_dataset_header.cpp, io/hdf5_layout_check.cpp): it says which field
// would be read past the message's end instead of reading it.

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "casmap/io/hdf5_header_walk.hpp"  // DecodeLe

namespace casmap::io::h5 {

/// The fields of one message's `bytes` (which must outlive it), read from the first byte on;
/// `what` ("layout message at byte N") starts every error.
class Cursor {
public:
    Cursor(const std::vector<std::uint8_t>& bytes, std::string what)
        : bytes_(bytes), what_(std::move(what)) {}

    // The next `n` bytes (at most 8) as a little-endian number; nullopt (error() set) when
    // they run past the message.
    std::optional<std::uint64_t> Get(std::size_t n, const std::string& part) {
        if (!Skip(n, part)) {
            return std::nullopt;
        }
        return DecodeLe(bytes_.data() + pos_ - n, n);
    }
    bool Skip(std::uint64_t n, const std::string& part) {
        if (bytes_.size() - pos_ < n) {
            return Fail(part + " at byte " + std::to_string(pos_) + " overrun" +
                        (part.back() == 's' ? "" : "s") + " its " + std::to_string(bytes_.size()) +
                        " bytes");
        }
        pos_ += n;
        return true;
    }
    bool Fail(const std::string& why) {
        error_ = what_ + ": " + why;
        return false;
    }
    [[nodiscard]] std::uint64_t left() const { return bytes_.size() - pos_; }
    [[nodiscard]] const std::uint8_t* here() const { return bytes_.data() + pos_; }
    [[nodiscard]] std::uint64_t pos() const { return pos_; }
    [[nodiscard]] const std::optional<std::string>& error() const { return error_; }

private:
    const std::vector<std::uint8_t>& bytes_;
    std::string what_;
    std::uint64_t pos_ = 0;
    std::optional<std::string> error_;
};

}  // namespace casmap::io::h5
