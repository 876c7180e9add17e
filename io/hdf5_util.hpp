#pragma once

// Thin RAII and checking helpers over the HDF5 C API for io/*.cpp (hdf5.h stays out of public
// module headers). All calls must happen under LibraryLock(): Debian's HDF5 is built without
// thread safety, and several threads (bench, drivers) may read or write run files at once.

#include <hdf5.h>

#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/io/hdf5_global_heap.hpp"

namespace casmap::io::h5 {

/// Serialises every HDF5 call of the process and silences HDF5's own error printing
/// (library code never prints; failures become exceptions here).
[[nodiscard]] std::unique_lock<std::mutex> LibraryLock();

/// An HDF5 identifier closed by the matching H5*close on destruction.
class Id {
public:
    using CloseFn = herr_t (*)(hid_t);
    Id() = default;
    Id(hid_t id, CloseFn close) : id_(id), close_(close) {}
    ~Id() { Reset(); }
    Id(Id&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = H5I_INVALID_HID; }
    Id& operator=(Id&& o) noexcept;
    Id(const Id&) = delete;
    Id& operator=(const Id&) = delete;

    [[nodiscard]] hid_t get() const { return id_; }
    void Reset();

private:
    hid_t id_ = H5I_INVALID_HID;
    CloseFn close_ = nullptr;
};

/// Throws std::runtime_error naming `what` when `id` < 0; else wraps it.
[[nodiscard]] Id Check(hid_t id, Id::CloseFn close, const std::string& what);
/// Throws std::runtime_error naming `what` when `status` < 0.
void Check(herr_t status, const std::string& what);

/// HDF5 file and memory types for the element types run files use.
template <typename T>
struct Types;
template <>
struct Types<float> {
    static hid_t File() { return H5T_IEEE_F32LE; }
    static hid_t Memory() { return H5T_NATIVE_FLOAT; }
    static constexpr H5T_class_t kClass = H5T_FLOAT;
};
template <>
struct Types<double> {
    static hid_t File() { return H5T_IEEE_F64LE; }
    static hid_t Memory() { return H5T_NATIVE_DOUBLE; }
    static constexpr H5T_class_t kClass = H5T_FLOAT;
};
template <>
struct Types<std::uint8_t> {
    static hid_t File() { return H5T_STD_U8LE; }
    static hid_t Memory() { return H5T_NATIVE_UINT8; }
    static constexpr H5T_class_t kClass = H5T_INTEGER;
};
template <>
struct Types<std::uint16_t> {
    static hid_t File() { return H5T_STD_U16LE; }
    static hid_t Memory() { return H5T_NATIVE_UINT16; }
    static constexpr H5T_class_t kClass = H5T_INTEGER;
};
template <>
struct Types<std::int32_t> {
    static hid_t File() { return H5T_STD_I32LE; }
    static hid_t Memory() { return H5T_NATIVE_INT32; }
    static constexpr H5T_class_t kClass = H5T_INTEGER;
};
template <>
struct Types<std::uint64_t> {
    static hid_t File() { return H5T_STD_U64LE; }
    static hid_t Memory() { return H5T_NATIVE_UINT64; }
    static constexpr H5T_class_t kClass = H5T_INTEGER;
};

/// Creates a file with fixed creation properties and no timestamps (byte-identical output).
[[nodiscard]] Id CreateFile(const std::string& path);
/// Creates a group without timestamps.
[[nodiscard]] Id CreateGroup(hid_t parent, const std::string& name);

/// Writes a dataset of `dims` (rank 1 or 2) from `data` (row-major, size = product of dims).
/// Large datasets are chunked and compressed (shuffle + deflate), deterministically.
void WriteDataset(hid_t parent,
                  const std::string& name,
                  hid_t file_type,
                  hid_t memory_type,
                  const std::vector<hsize_t>& dims,
                  const void* data);

template <typename T>
void WriteDataset(hid_t parent,
                  const std::string& name,
                  const std::vector<hsize_t>& dims,
                  const std::vector<T>& data) {
    WriteDataset(parent, name, Types<T>::File(), Types<T>::Memory(), dims, data.data());
}

/// Fills rows [first, first + count) of a dataset into `out` (row-major, memory type).
using RowFill = std::function<void(std::size_t first, std::size_t count, void* out)>;

/// Writes a dataset of `dims` whose rows come from `fill`, one chunk at a time: a large array
/// is never held whole (the same file bytes as WriteDataset of the whole array). Exceptions of
/// `fill` propagate.
void WriteDataset(hid_t parent,
                  const std::string& name,
                  hid_t file_type,
                  hid_t memory_type,
                  const std::vector<hsize_t>& dims,
                  const RowFill& fill);

template <typename T, typename Fill>
void WriteRows(hid_t parent,
               const std::string& name,
               const std::vector<hsize_t>& dims,
               const Fill& fill) {  // fill(std::size_t first, std::size_t count, T* out)
    WriteDataset(parent, name, Types<T>::File(), Types<T>::Memory(), dims,
                 RowFill([&fill](std::size_t first, std::size_t count, void* out) {
                     fill(first, count, static_cast<T*>(out));
                 }));
}

/// Attributes: scalars, 1-D double arrays and UTF-8 fixed-length strings (NUL-padded; h5py
/// reads them as bytes). casmap writes no variable-length data: those live in the global heap,
/// which HDF5 1.10 decodes unsafely (hdf5_global_heap.hpp).
void WriteAttribute(hid_t object, const std::string& name, double value);
void WriteAttribute(hid_t object, const std::string& name, std::int32_t value);
void WriteAttribute(hid_t object, const std::string& name, std::uint64_t value);
void WriteAttribute(hid_t object, const std::string& name, const std::vector<double>& values);
void WriteAttribute(hid_t object, const std::string& name, const std::string& value);

/// Writes a scalar UTF-8 fixed-length string dataset (NUL-padded, at least one byte).
void WriteStringDataset(hid_t parent, const std::string& name, const std::string& value);

/// How messages name an attribute: "/scans attribute start_angle_rad".
[[nodiscard]] std::string AttributeWhere(const std::string& object, const std::string& name);

/// The largest size a dataset dimension may have, and what it counts ("scans", "beams").
struct DimLimit {
    std::uint64_t max = 0;
    const char* what = "";
};

/// Read side: every failure is an InputError naming the file and the object path.
class FileReader {
public:
    /// Opens `path` read-only; throws InputError if it is missing or not an HDF5 file.
    explicit FileReader(std::string path);
    /// Opens the bytes of an HDF5 file held in memory (core driver); `name` names it.
    FileReader(const void* image, std::size_t size, std::string name);

    [[nodiscard]] const std::string& path() const { return path_; }
    /// True if the link `object` (an absolute path like "/scans/labels") exists. Each object on
    /// the way must be a hard link whose header blocks lie inside the file (else InputError).
    [[nodiscard]] bool Has(const std::string& object) const;
    /// Names in a group, sorted by name.
    [[nodiscard]] std::vector<std::string> Children(const std::string& group) const;

    /// Reads a dataset of `rank` dimensions whose element class matches T's (integer or float);
    /// HDF5 converts the element size. `dims` receives the shape. Each dimension is checked
    /// against `limits` (one per dimension) before anything is allocated.
    template <typename T>
    [[nodiscard]] std::vector<T> Read(const std::string& dataset,
                                      int rank,
                                      std::vector<hsize_t>& dims,
                                      const std::vector<DimLimit>& limits) const {
        std::vector<T> out;
        ReadRaw(dataset, rank, Types<T>::kClass, Types<T>::Memory(), dims, limits,
                [&](std::size_t n) -> void* {
                    out.resize(n);
                    return out.data();
                });
        return out;
    }

    /// Attribute readers; nullopt when the attribute is absent, InputError when it has the
    /// wrong type or shape.
    [[nodiscard]] std::optional<double> ReadDouble(const std::string& object,
                                                   const std::string& name) const;
    [[nodiscard]] std::optional<std::int64_t> ReadInteger(const std::string& object,
                                                          const std::string& name) const;
    [[nodiscard]] std::optional<std::uint64_t> ReadUnsigned(const std::string& object,
                                                            const std::string& name) const;
    [[nodiscard]] std::optional<std::vector<double>> ReadDoubles(const std::string& object,
                                                                 const std::string& name,
                                                                 std::size_t max_count) const;
    /// A string attribute, fixed or variable length; a variable-length one is read only from a
    /// file whose global heap passes FindCorruptGlobalHeap (else InputError naming it).
    [[nodiscard]] std::optional<std::string> ReadString(const std::string& object,
                                                        const std::string& name) const;
    /// A scalar string dataset (absent: nullopt), with the same rules as ReadString.
    [[nodiscard]] std::optional<std::string> ReadStringDataset(const std::string& dataset) const;

    /// InputError "<file>: <object> = <value> (<rule>)".
    [[nodiscard]] InputError Error(const std::string& object,
                                   const std::string& value,
                                   const std::string& rule) const;

private:
    template <typename Alloc>
    void ReadRaw(const std::string& dataset,
                 int rank,
                 H5T_class_t expected,
                 hid_t memory_type,
                 std::vector<hsize_t>& dims,
                 const std::vector<DimLimit>& limits,
                 Alloc alloc) const {
        ReadRawImpl(
            dataset, rank, expected, memory_type, dims, limits,
            [](std::size_t n, void* ctx) { return (*static_cast<Alloc*>(ctx))(n); }, &alloc);
    }
    void ReadRawImpl(const std::string& dataset,
                     int rank,
                     H5T_class_t expected,
                     hid_t memory_type,
                     std::vector<hsize_t>& dims,
                     const std::vector<DimLimit>& limits,
                     void* (*alloc)(std::size_t, void*),
                     void* ctx) const;
    [[nodiscard]] Id OpenAttribute(const std::string& object,
                                   const std::string& name,
                                   H5T_class_t expected) const;

    /// Throws InputError naming `where` unless the file's global heap is safe for HDF5 to read
    /// (checked once per reader).
    void CheckGlobalHeap(const std::string& where, const std::string& value) const;
    /// Throws InputError naming `object` unless its attribute messages are safe for HDF5 to
    /// decode (FindCorruptAttributeMessages; checked once per object).
    void CheckAttributeMessages(const std::string& object) const;
    /// Before H5Fopen: throws InputError unless the superblock is at byte 0 and the root group's
    /// object header blocks lie inside the file (FindCorruptHeaderBlocks).
    void CheckBeforeOpen() const;
    /// Before HDF5 loads the object header of `object` (whose parent group is checked): throws
    /// InputError unless its link is a hard link and its header blocks lie inside the file.
    void CheckHeaderBlocks(const std::string& object) const;
    /// The object header address of `object` after those checks; nullopt if it does not exist.
    [[nodiscard]] std::optional<std::uint64_t> HeaderAddress(const std::string& object) const;
    /// Before H5Dread of the open dataset `handle`: throws InputError naming `dataset` unless
    /// its stored chunks come out of their filters at their chunk's size (FindBadChunk).
    void CheckChunks(const std::string& dataset, hid_t handle) const;
    /// Throws InputError naming `dataset` unless the messages H5Dopen2 decodes from its object
    /// header are safe for HDF5 to decode (FindCorruptDatasetMessages).
    void CheckDatasetMessages(const std::string& dataset) const;
    [[nodiscard]] std::optional<std::string> CheckBytes(
        const std::string& where,
        const std::string& value,
        const std::function<std::optional<std::string>(std::uint64_t, const ReadAt&)>& check) const;
    [[nodiscard]] std::string ReadStringValue(hid_t object,
                                              hid_t type,
                                              const std::string& where,
                                              bool attribute) const;

    std::string path_;
    Id file_;
    const void* image_ = nullptr;  // the bytes of a file image (else the file at path_)
    std::size_t image_size_ = 0;
    mutable std::optional<std::string> heap_problem_;  // "" once checked and found safe
    mutable std::map<std::string, std::string> attribute_problems_;  // per object; "" = safe
    mutable std::map<std::string, std::uint64_t> header_addresses_;  // objects checked, by path
};

}  // namespace casmap::io::h5
