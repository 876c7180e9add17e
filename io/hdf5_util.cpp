#include "casmap/io/hdf5_util.hpp"

// The write side of hdf5_util.hpp (and the shared Id, Check, LibraryLock); FileReader is in
// hdf5_file_reader.cpp.

#include <algorithm>
#include <optional>
#include <stdexcept>

#include "casmap/io/hdf5_chunk_writer.hpp"

namespace casmap::io::h5 {
namespace {

// Object creation properties shared by groups and datasets: no access/modification times, so
// the same content gives the same bytes.
void NoTimes(hid_t plist) { Check(H5Pset_obj_track_times(plist, false), "H5Pset_obj_track_times"); }

Id ScalarSpace() { return Check(H5Screate(H5S_SCALAR), H5Sclose, "H5Screate"); }

// A fixed-length UTF-8 string type holding `value` (NUL-padded; HDF5 needs at least one byte).
Id FixedUtf8StringType(const std::string& value) {
    Id type = Check(H5Tcopy(H5T_C_S1), H5Tclose, "H5Tcopy");
    Check(H5Tset_size(type.get(), std::max<std::size_t>(value.size(), 1)), "H5Tset_size");
    Check(H5Tset_strpad(type.get(), H5T_STR_NULLPAD), "H5Tset_strpad");
    Check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "H5Tset_cset");
    return type;
}

void WriteAttributeRaw(hid_t object,
                       const std::string& name,
                       hid_t file_type,
                       hid_t memory_type,
                       hid_t space,
                       const void* data) {
    const Id acpl = Check(H5Pcreate(H5P_ATTRIBUTE_CREATE), H5Pclose, "H5Pcreate");
    const Id attr =
        Check(H5Acreate2(object, name.c_str(), file_type, space, acpl.get(), H5P_DEFAULT), H5Aclose,
              "H5Acreate2 " + name);
    Check(H5Awrite(attr.get(), memory_type, data), "H5Awrite " + name);
}

}  // namespace

std::string AttributeWhere(const std::string& object, const std::string& name) {
    return object + " attribute " + name;
}

std::unique_lock<std::mutex> LibraryLock() {
    static std::mutex mutex;
    static std::once_flag silence;
    std::unique_lock<std::mutex> lock(mutex);
    std::call_once(silence, [] { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); });
    return lock;
}

Id& Id::operator=(Id&& o) noexcept {
    if (this != &o) {
        Reset();
        id_ = o.id_;
        close_ = o.close_;
        o.id_ = H5I_INVALID_HID;
    }
    return *this;
}

void Id::Reset() {
    if (id_ >= 0 && close_ != nullptr) {
        close_(id_);
    }
    id_ = H5I_INVALID_HID;
}

Id Check(hid_t id, Id::CloseFn close, const std::string& what) {
    if (id < 0) {
        throw std::runtime_error("HDF5 call failed: " + what);
    }
    return Id(id, close);
}

void Check(herr_t status, const std::string& what) {
    if (status < 0) {
        throw std::runtime_error("HDF5 call failed: " + what);
    }
}

Id CreateFile(const std::string& path) {
    const Id fcpl = Check(H5Pcreate(H5P_FILE_CREATE), H5Pclose, "H5Pcreate");
    NoTimes(fcpl.get());  // the root group
    const Id fapl = Check(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "H5Pcreate");
    Check(H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG), "H5Pset_fclose_degree");
    Check(H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_EARLIEST, H5F_LIBVER_V18),
          "H5Pset_libver_bounds");
    return Check(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, fcpl.get(), fapl.get()), H5Fclose,
                 "H5Fcreate " + path);
}

Id CreateGroup(hid_t parent, const std::string& name) {
    const Id gcpl = Check(H5Pcreate(H5P_GROUP_CREATE), H5Pclose, "H5Pcreate");
    NoTimes(gcpl.get());
    return Check(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, gcpl.get(), H5P_DEFAULT), H5Gclose,
                 "H5Gcreate2 " + name);
}

namespace {
// `data` (whole array) or, when null, `fill` (chunk by chunk).
void WriteDatasetFrom(hid_t parent,
                      const std::string& name,
                      hid_t file_type,
                      hid_t memory_type,
                      const std::vector<hsize_t>& dims,
                      const void* data,
                      const RowFill* fill) {
    const Id space = Check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                           H5Sclose, "H5Screate_simple " + name);
    const Id dcpl = Check(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "H5Pcreate");
    NoTimes(dcpl.get());
    hsize_t count = 1;
    for (const hsize_t d : dims) {
        count *= d;
    }
    // Chunk whole rows, about 256 KiB per chunk; small datasets stay contiguous.
    const std::size_t element = H5Tget_size(file_type);
    std::vector<hsize_t> chunk;  // empty: contiguous
    std::optional<ChunkWriter> writer;
    if (count >= 1024 && H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0) {
        chunk = dims;
        const hsize_t row_bytes = (dims.size() > 1 ? dims[1] : 1) * element;
        chunk[0] = std::clamp<hsize_t>(262144 / std::max<hsize_t>(row_bytes, 1), 1, dims[0]);
        Check(H5Pset_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data()),
              "H5Pset_chunk " + name);
        bool shuffle = element > 1;
        if (H5Tequal(file_type, memory_type) > 0) {  // else HDF5 converts and filters
            writer.emplace(dims, chunk, element, data, fill);
            shuffle = writer->Choose();
        }
        if (shuffle) {
            Check(H5Pset_shuffle(dcpl.get()), "H5Pset_shuffle");
        }
        Check(H5Pset_deflate(dcpl.get(), 1), "H5Pset_deflate");
    }
    const Id dataset = Check(H5Dcreate2(parent, name.c_str(), file_type, space.get(), H5P_DEFAULT,
                                        dcpl.get(), H5P_DEFAULT),
                             H5Dclose, "H5Dcreate2 " + name);
    if (count > 0) {
        if (writer) {
            writer->Write(dataset.get(), dims.size());
            return;
        }
        std::vector<unsigned char> whole;
        if (data == nullptr) {
            whole.resize(static_cast<std::size_t>(count) * H5Tget_size(memory_type));
            (*fill)(0, static_cast<std::size_t>(dims[0]), whole.data());
            data = whole.data();
        }
        Check(H5Dwrite(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data),
              "H5Dwrite " + name);
    }
}
}  // namespace

void WriteDataset(hid_t parent,
                  const std::string& name,
                  hid_t file_type,
                  hid_t memory_type,
                  const std::vector<hsize_t>& dims,
                  const void* data) {
    WriteDatasetFrom(parent, name, file_type, memory_type, dims, data, nullptr);
}

void WriteDataset(hid_t parent,
                  const std::string& name,
                  hid_t file_type,
                  hid_t memory_type,
                  const std::vector<hsize_t>& dims,
                  const RowFill& fill) {
    WriteDatasetFrom(parent, name, file_type, memory_type, dims, nullptr, &fill);
}

void WriteAttribute(hid_t object, const std::string& name, double value) {
    WriteAttributeRaw(object, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, ScalarSpace().get(), &value);
}

void WriteAttribute(hid_t object, const std::string& name, std::int32_t value) {
    WriteAttributeRaw(object, name, H5T_STD_I32LE, H5T_NATIVE_INT32, ScalarSpace().get(), &value);
}

void WriteAttribute(hid_t object, const std::string& name, std::uint64_t value) {
    WriteAttributeRaw(object, name, H5T_STD_U64LE, H5T_NATIVE_UINT64, ScalarSpace().get(), &value);
}

void WriteAttribute(hid_t object, const std::string& name, const std::vector<double>& values) {
    const hsize_t n = values.size();
    const Id space = Check(H5Screate_simple(1, &n, nullptr), H5Sclose, "H5Screate_simple");
    WriteAttributeRaw(object, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, space.get(), values.data());
}

void WriteAttribute(hid_t object, const std::string& name, const std::string& value) {
    const Id type = FixedUtf8StringType(value);
    const std::string padded = value.empty() ? std::string(1, '\0') : value;
    WriteAttributeRaw(object, name, type.get(), type.get(), ScalarSpace().get(), padded.data());
}

void WriteStringDataset(hid_t parent, const std::string& name, const std::string& value) {
    const Id type = FixedUtf8StringType(value);
    const std::string padded = value.empty() ? std::string(1, '\0') : value;
    const Id dcpl = Check(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "H5Pcreate");
    NoTimes(dcpl.get());
    const Id d = Check(H5Dcreate2(parent, name.c_str(), type.get(), ScalarSpace().get(),
                                  H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
                       H5Dclose, "H5Dcreate2 " + name);
    Check(H5Dwrite(d.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, padded.data()),
          "H5Dwrite " + name);
}

}  // namespace casmap::io::h5
