#include "casmap/io/hdf5_util.hpp"

// FileReader's checks of the file's bytes before HDF5 decodes them: the global heap
// (hdf5_global_heap.hpp), an object's attribute messages (hdf5_object_header.hpp) and a
// dataset's own messages (hdf5_dataset_header.hpp).

#include <algorithm>
#include <array>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "casmap/io/hdf5_chunk_check.hpp"
#include "casmap/io/hdf5_dataset_header.hpp"
#include "casmap/io/hdf5_global_heap.hpp"
#include "casmap/io/hdf5_header_walk.hpp"
#include "casmap/io/hdf5_object_header.hpp"

namespace casmap::io::h5 {

// Runs `check` over the file's bytes: the image in memory, or the file at path_.
std::optional<std::string> FileReader::CheckBytes(
    const std::string& where,
    const std::string& value,
    const std::function<std::optional<std::string>(std::uint64_t, const ReadAt&)>& check) const {
    if (image_ != nullptr) {
        const auto* bytes = static_cast<const std::uint8_t*>(image_);
        return check(image_size_, [&](std::uint64_t offset, std::size_t size, void* out) {
            if (offset >= image_size_ || size == 0) {  // `out` may be null for 0 bytes
                return std::size_t{0};
            }
            const std::size_t n =
                static_cast<std::size_t>(std::min<std::uint64_t>(size, image_size_ - offset));
            std::memcpy(out, bytes + offset, n);
            return n;
        });
    }
    std::ifstream in(path_, std::ios::binary);
    std::error_code ec;
    const std::uintmax_t file_size = std::filesystem::file_size(path_, ec);
    if (!in || ec) {
        throw Error(where, value, "the file cannot be read to check it");
    }
    return check(file_size, [&](std::uint64_t offset, std::size_t size, void* out) {
        in.clear();
        in.seekg(static_cast<std::streamoff>(offset));
        in.read(static_cast<char*>(out), static_cast<std::streamsize>(size));
        return static_cast<std::size_t>(in.gcount());
    });
}

void FileReader::CheckGlobalHeap(const std::string& where, const std::string& value) const {
    if (!heap_problem_) {
        heap_problem_ = CheckBytes(where, value, FindCorruptGlobalHeap).value_or("");
    }
    if (!heap_problem_->empty()) {
        throw Error(where, value, "corrupt file: " + *heap_problem_);
    }
}

namespace {
// HDF5 looks for the superblock at byte 0, 512, 1024, 2048, ... (a user block before it); casmap's
// checks read it at byte 0 only.
std::optional<std::string> FindMovedSuperblock(std::uint64_t file_size, const ReadAt& read) {
    constexpr std::array<std::uint8_t, 8> kSignature = {0x89, 'H',  'D',  'F',
                                                        '\r', '\n', 0x1a, '\n'};
    std::array<std::uint8_t, 8> head{};
    for (std::uint64_t at = 0; at + head.size() <= file_size; at = at == 0 ? 512 : 2 * at) {
        if (read(at, head.size(), head.data()) == head.size() && head == kSignature) {
            if (at == 0) {
                return std::nullopt;
            }
            return "its superblock is at byte " + std::to_string(at) +
                   " after a user block; casmap reads files whose superblock is at byte 0";
        }
    }
    return std::nullopt;  // not HDF5: H5Fopen says so
}
}  // namespace

void FileReader::CheckBeforeOpen() const {
    const std::optional<std::string> problem =
        CheckBytes("/", "", [](std::uint64_t size, const ReadAt& read) {
            if (std::optional<std::string> why = FindMovedSuperblock(size, read)) {
                return why;
            }
            // H5Fopen rejects a file shorter than its end-of-file address before it loads the
            // root group ("truncated file").
            const std::optional<Superblock> sb = ReadSuperblock(size, read);
            if (!sb || size < sb->end_of_file) {
                return std::optional<std::string>();
            }
            return FindCorruptHeaderBlocks(std::nullopt, size, read);
        });
    if (problem) {
        throw Error("/", "", "corrupt file: " + *problem);
    }
}

void FileReader::CheckHeaderBlocks(const std::string& object) const {
    if (header_addresses_.count(object) != 0) {
        return;
    }
    // The link's target address, read from the parent group (checked already) without loading
    // the target's header; soft and external links (another file) are not followed.
    H5L_info_t link{};
    if (H5Lget_info(file_.get(), object.c_str(), &link, H5P_DEFAULT) < 0) {
        throw Error(object, "", "corrupt file: its link cannot be read");
    }
    if (link.type != H5L_TYPE_HARD) {
        throw Error(object, "", "must be a hard link (casmap follows no soft or external link)");
    }
    const std::optional<std::string> problem =
        CheckBytes(object, "", [&](std::uint64_t size, const ReadAt& read) {
            return FindCorruptHeaderBlocks(link.u.address, size, read);
        });
    if (problem) {
        throw Error(object, "", "corrupt file: " + *problem);
    }
    header_addresses_[object] = link.u.address;
}

std::optional<std::uint64_t> FileReader::HeaderAddress(const std::string& object) const {
    if (object == "/") {  // checked before H5Fopen loaded it
        H5O_info_t info{};
        if (H5Oget_info_by_name2(file_.get(), "/", &info, H5O_INFO_BASIC, H5P_DEFAULT) < 0) {
            return std::nullopt;
        }
        return info.addr;
    }
    if (!Has(object)) {
        return std::nullopt;
    }
    return header_addresses_.at(object);
}

void FileReader::CheckDatasetMessages(const std::string& dataset) const {
    const std::optional<std::uint64_t> address = HeaderAddress(dataset);
    if (!address) {
        throw Error(dataset, "", "corrupt file: its object header cannot be read");
    }
    const std::optional<std::string> problem =
        CheckBytes(dataset, "", [&](std::uint64_t size, const ReadAt& read) {
            return FindCorruptDatasetMessages(*address, size, read);
        });
    if (problem) {
        throw Error(dataset, "", "corrupt file: " + *problem);
    }
}

void FileReader::CheckChunks(const std::string& dataset, hid_t handle) const {
    std::uint64_t size = image_size_;
    if (image_ == nullptr) {
        std::error_code ec;
        size = std::filesystem::file_size(path_, ec);
        if (ec) {
            throw Error(dataset, "", "the file cannot be read to check it");
        }
    }
    if (const std::optional<std::string> problem = FindBadChunk(handle, size)) {
        const bool unsupported = problem->rfind(kUnsupportedFilter, 0) == 0;
        throw Error(dataset, "",
                    (unsupported ? "unsupported encoding: " : "corrupt file: ") + *problem);
    }
}

void FileReader::CheckAttributeMessages(const std::string& object) const {
    auto [it, fresh] = attribute_problems_.try_emplace(object);
    if (fresh) {
        const std::optional<std::uint64_t> address = HeaderAddress(object);
        if (!address) {
            it->second = "its object header cannot be read";
        } else {
            it->second = CheckBytes(object, "", [&](std::uint64_t size, const ReadAt& read) {
                             return FindCorruptAttributeMessages(*address, size, read);
                         }).value_or("");
        }
    }
    if (!it->second.empty()) {
        throw Error(object, "", "corrupt file: " + it->second);
    }
}

}  // namespace casmap::io::h5
