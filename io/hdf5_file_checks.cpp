#include "casmap/io/hdf5_util.hpp"

// FileReader's checks of the file's bytes before HDF5 decodes them: the global heap
// (hdf5_global_heap.hpp), an object's attribute messages (hdf5_object_header.hpp) and a
// dataset's own messages (hdf5_dataset_header.hpp).

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "casmap/io/hdf5_dataset_header.hpp"
#include "casmap/io/hdf5_global_heap.hpp"
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
            if (offset >= image_size_) {
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

void FileReader::CheckDatasetMessages(const std::string& dataset) const {
    H5O_info_t info{};
    if (H5Oget_info_by_name2(file_.get(), dataset.c_str(), &info, H5O_INFO_BASIC, H5P_DEFAULT) <
        0) {
        throw Error(dataset, "", "corrupt file: its object header cannot be read");
    }
    const std::optional<std::string> problem =
        CheckBytes(dataset, "", [&](std::uint64_t size, const ReadAt& read) {
            return FindCorruptDatasetMessages(info.addr, size, read);
        });
    if (problem) {
        throw Error(dataset, "", "corrupt file: " + *problem);
    }
}

void FileReader::CheckAttributeMessages(const std::string& object) const {
    auto [it, fresh] = attribute_problems_.try_emplace(object);
    if (fresh) {
        H5O_info_t info{};
        if (H5Oget_info_by_name2(file_.get(), object.c_str(), &info, H5O_INFO_BASIC, H5P_DEFAULT) <
            0) {
            it->second = "its object header cannot be read";
        } else {
            it->second = CheckBytes(object, "", [&](std::uint64_t size, const ReadAt& read) {
                             return FindCorruptAttributeMessages(info.addr, size, read);
                         }).value_or("");
        }
    }
    if (!it->second.empty()) {
        throw Error(object, "", "corrupt file: " + it->second);
    }
}

}  // namespace casmap::io::h5
