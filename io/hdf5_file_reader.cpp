#include "casmap/io/hdf5_util.hpp"

// The read side of hdf5_util.hpp: FileReader, which turns every failure into an InputError
// naming the file and the object, and checks the bytes HDF5 would decode unsafely first
// (io/hdf5_file_checks.cpp).

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <optional>
#include <utility>

namespace casmap::io::h5 {
namespace {

std::string ShapeText(const std::vector<hsize_t>& dims) {
    std::string text;
    for (std::size_t i = 0; i < dims.size(); ++i) {
        text += (i == 0 ? "" : " x ") + std::to_string(dims[i]);
    }
    return dims.empty() ? "scalar" : text;
}

std::string ClassName(H5T_class_t c) {
    switch (c) {
        case H5T_INTEGER:
            return "integer";
        case H5T_FLOAT:
            return "float";
        case H5T_STRING:
            return "string";
        default:
            return "type class " + std::to_string(static_cast<int>(c));
    }
}

// The widest integer or float element casmap reads (HDF5 knows no wider native number).
constexpr std::size_t kMaxNumberBytes = 16;

Id Utf8StringType() {
    Id type = Check(H5Tcopy(H5T_C_S1), H5Tclose, "H5Tcopy");
    Check(H5Tset_size(type.get(), H5T_VARIABLE), "H5Tset_size");
    Check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "H5Tset_cset");
    return type;
}

}  // namespace

FileReader::FileReader(std::string path) : path_(std::move(path)) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path_, ec)) {
        throw MakeInputError(path_, "run file", "", "does not exist or is not a regular file");
    }
    const Id fapl = Check(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "H5Pcreate");
    Check(H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG), "H5Pset_fclose_degree");
    CheckBeforeOpen();
    const hid_t file = H5Fopen(path_.c_str(), H5F_ACC_RDONLY, fapl.get());
    if (file < 0) {
        throw MakeInputError(path_, "run file", "", "not a readable HDF5 file");
    }
    file_ = Id(file, H5Fclose);
}

FileReader::FileReader(const void* image, std::size_t size, std::string name)
    : path_(std::move(name)) {
    const Id fapl = Check(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "H5Pcreate");
    Check(H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG), "H5Pset_fclose_degree");
    // The core driver reads the file image from memory; nothing is written back.
    Check(H5Pset_fapl_core(fapl.get(), 1 << 16, false), "H5Pset_fapl_core");
    image_ = image;
    image_size_ = size;
    if (size == 0 || H5Pset_file_image(fapl.get(), const_cast<void*>(image), size) < 0) {
        throw MakeInputError(path_, "run file", "", "not a readable HDF5 file");
    }
    CheckBeforeOpen();
    const hid_t file = H5Fopen(path_.c_str(), H5F_ACC_RDONLY, fapl.get());
    if (file < 0) {
        throw MakeInputError(path_, "run file", "", "not a readable HDF5 file");
    }
    file_ = Id(file, H5Fclose);
}

InputError FileReader::Error(const std::string& object,
                             const std::string& value,
                             const std::string& rule) const {
    return MakeInputError(path_, object, value, rule);
}

bool FileReader::Has(const std::string& object) const {
    // Check each link on the way so a missing parent group is "absent", not an error.
    std::size_t pos = 1;
    while (pos <= object.size()) {
        const std::size_t next = object.find('/', pos);
        const std::string prefix = object.substr(0, next);
        if (H5Lexists(file_.get(), prefix.c_str(), H5P_DEFAULT) <= 0) {
            return false;
        }
        CheckHeaderBlocks(prefix);  // before HDF5 loads it to look inside or open it
        if (next == std::string::npos) {
            break;
        }
        pos = next + 1;
    }
    return true;
}

std::vector<std::string> FileReader::Children(const std::string& group) const {
    std::vector<std::string> names;
    const Id g =
        Check(H5Gopen2(file_.get(), group.c_str(), H5P_DEFAULT), H5Gclose, "H5Gopen2 " + group);
    H5G_info_t info{};
    Check(H5Gget_info(g.get(), &info), "H5Gget_info " + group);
    for (hsize_t i = 0; i < info.nlinks; ++i) {
        const ssize_t len = H5Lget_name_by_idx(g.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr,
                                               0, H5P_DEFAULT);
        if (len < 0) {
            throw Error(group, "", "cannot list its members");
        }
        std::string name(static_cast<std::size_t>(len) + 1, '\0');
        H5Lget_name_by_idx(g.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), name.size(),
                           H5P_DEFAULT);
        name.resize(static_cast<std::size_t>(len));
        names.push_back(name);
    }
    std::sort(names.begin(), names.end());
    return names;
}

void FileReader::ReadRawImpl(const std::string& dataset,
                             int rank,
                             H5T_class_t expected,
                             hid_t memory_type,
                             std::vector<hsize_t>& dims,
                             const std::vector<DimLimit>& limits,
                             void* (*alloc)(std::size_t, void*),
                             void* ctx) const {
    if (!Has(dataset)) {
        throw Error(dataset, "", "required dataset is missing");
    }
    // H5Dopen2 decodes the dataset's header messages, and so does H5Oget_info for anything
    // beyond the basic fields (a dataset's storage size: layout, pipeline, external files).
    CheckDatasetMessages(dataset);
    H5O_info_t info{};
    if (H5Oget_info_by_name2(file_.get(), dataset.c_str(), &info, H5O_INFO_BASIC, H5P_DEFAULT) <
            0 ||
        info.type != H5O_TYPE_DATASET) {
        throw Error(dataset, "", "must be a dataset");
    }
    const Id d =
        Check(H5Dopen2(file_.get(), dataset.c_str(), H5P_DEFAULT), H5Dclose, "H5Dopen2 " + dataset);
    const Id type = Check(H5Dget_type(d.get()), H5Tclose, "H5Dget_type " + dataset);
    const H5T_class_t cls = H5Tget_class(type.get());
    if (cls != expected) {
        throw Error(dataset, ClassName(cls), "element type must be " + ClassName(expected));
    }
    // H5Dread sizes its conversion buffer by the file's element size.
    if (H5Tget_size(type.get()) > kMaxNumberBytes) {
        throw Error(
            dataset, std::to_string(H5Tget_size(type.get())) + "-byte elements",
            "element size limit " + std::to_string(kMaxNumberBytes) + " bytes, see docs/limits.md");
    }
    const Id space = Check(H5Dget_space(d.get()), H5Sclose, "H5Dget_space " + dataset);
    const int ndims = H5Sget_simple_extent_ndims(space.get());
    dims.assign(static_cast<std::size_t>(std::max(ndims, 0)), 0);
    if (ndims > 0) {
        H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
    }
    if (ndims != rank) {
        throw Error(dataset, "shape " + ShapeText(dims),
                    "must have " + std::to_string(rank) + " dimension(s)");
    }
    std::size_t count = 1;
    for (std::size_t k = 0; k < dims.size(); ++k) {
        if (k < limits.size() && dims[k] > limits[k].max) {
            throw Error(dataset, "shape " + ShapeText(dims),
                        "dimension " + std::to_string(k + 1) + " (" + limits[k].what + ") limit " +
                            std::to_string(limits[k].max) + ", see docs/limits.md");
        }
        count *= static_cast<std::size_t>(dims[k]);
    }
    if (count > 0) {
        CheckChunks(dataset, d.get());
    }
    void* buffer = alloc(count, ctx);
    if (count > 0 && H5Dread(d.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer) < 0) {
        throw Error(dataset, "", "cannot be read (corrupt or unsupported encoding)");
    }
}

Id FileReader::OpenAttribute(const std::string& object,
                             const std::string& name,
                             H5T_class_t expected) const {
    CheckAttributeMessages(object);  // HDF5 decodes every attribute of the object below
    if (H5Aexists_by_name(file_.get(), object.c_str(), name.c_str(), H5P_DEFAULT) <= 0) {
        return Id();
    }
    Id attr =
        Check(H5Aopen_by_name(file_.get(), object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
              H5Aclose, "H5Aopen_by_name " + name);
    const Id type = Check(H5Aget_type(attr.get()), H5Tclose, "H5Aget_type " + name);
    const H5T_class_t cls = H5Tget_class(type.get());
    if (cls != expected) {
        throw Error(AttributeWhere(object, name), ClassName(cls),
                    "attribute type must be " + ClassName(expected));
    }
    return attr;
}

namespace {
// Attribute strings hold names and the effective configuration (YAML text).
constexpr std::size_t kMaxStringBytes = std::size_t{4} << 20;

hssize_t AttributeElements(hid_t attr) {
    const Id space = Check(H5Aget_space(attr), H5Sclose, "H5Aget_space");
    return H5Sget_simple_extent_npoints(space.get());
}
}  // namespace

std::optional<double> FileReader::ReadDouble(const std::string& object,
                                             const std::string& name) const {
    const Id attr = OpenAttribute(object, name, H5T_FLOAT);
    if (attr.get() < 0) {
        return std::nullopt;
    }
    if (AttributeElements(attr.get()) != 1) {
        throw Error(AttributeWhere(object, name), "", "must be a single number");
    }
    double value = 0.0;
    Check(H5Aread(attr.get(), H5T_NATIVE_DOUBLE, &value), "H5Aread " + name);
    return value;
}

std::optional<std::int64_t> FileReader::ReadInteger(const std::string& object,
                                                    const std::string& name) const {
    const Id attr = OpenAttribute(object, name, H5T_INTEGER);
    if (attr.get() < 0) {
        return std::nullopt;
    }
    if (AttributeElements(attr.get()) != 1) {
        throw Error(AttributeWhere(object, name), "", "must be a single integer");
    }
    std::int64_t value = 0;
    Check(H5Aread(attr.get(), H5T_NATIVE_INT64, &value), "H5Aread " + name);
    return value;
}

std::optional<std::uint64_t> FileReader::ReadUnsigned(const std::string& object,
                                                      const std::string& name) const {
    const Id attr = OpenAttribute(object, name, H5T_INTEGER);
    if (attr.get() < 0) {
        return std::nullopt;
    }
    const Id type = Check(H5Aget_type(attr.get()), H5Tclose, "H5Aget_type " + name);
    if (AttributeElements(attr.get()) != 1 || H5Tget_sign(type.get()) != H5T_SGN_NONE) {
        throw Error(AttributeWhere(object, name), "", "must be a single unsigned integer");
    }
    std::uint64_t value = 0;
    Check(H5Aread(attr.get(), H5T_NATIVE_UINT64, &value), "H5Aread " + name);
    return value;
}

std::optional<std::vector<double>> FileReader::ReadDoubles(const std::string& object,
                                                           const std::string& name,
                                                           std::size_t max_count) const {
    const Id attr = OpenAttribute(object, name, H5T_FLOAT);
    if (attr.get() < 0) {
        return std::nullopt;
    }
    const hssize_t n = AttributeElements(attr.get());
    if (n > static_cast<hssize_t>(max_count)) {
        throw Error(AttributeWhere(object, name), std::to_string(n) + " values",
                    "limit " + std::to_string(max_count) + ", see docs/limits.md");
    }
    std::vector<double> values(static_cast<std::size_t>(std::max<hssize_t>(n, 0)));
    if (!values.empty()) {
        Check(H5Aread(attr.get(), H5T_NATIVE_DOUBLE, values.data()), "H5Aread " + name);
    }
    return values;
}

std::optional<std::string> FileReader::ReadString(const std::string& object,
                                                  const std::string& name) const {
    const Id attr = OpenAttribute(object, name, H5T_STRING);
    if (attr.get() < 0) {
        return std::nullopt;
    }
    if (AttributeElements(attr.get()) != 1) {
        throw Error(AttributeWhere(object, name), "", "must be a single string");
    }
    const Id type = Check(H5Aget_type(attr.get()), H5Tclose, "H5Aget_type " + name);
    return ReadStringValue(attr.get(), type.get(), AttributeWhere(object, name), true);
}

std::optional<std::string> FileReader::ReadStringDataset(const std::string& dataset) const {
    if (!Has(dataset)) {
        return std::nullopt;
    }
    CheckDatasetMessages(dataset);
    const Id d =
        Check(H5Dopen2(file_.get(), dataset.c_str(), H5P_DEFAULT), H5Dclose, "H5Dopen2 " + dataset);
    const Id type = Check(H5Dget_type(d.get()), H5Tclose, "H5Dget_type " + dataset);
    const H5T_class_t cls = H5Tget_class(type.get());
    if (cls != H5T_STRING) {
        throw Error(dataset, ClassName(cls), "dataset type must be string");
    }
    const Id space = Check(H5Dget_space(d.get()), H5Sclose, "H5Dget_space " + dataset);
    if (H5Sget_simple_extent_npoints(space.get()) != 1) {
        throw Error(dataset, "", "must be a single string");
    }
    CheckChunks(dataset, d.get());
    return ReadStringValue(d.get(), type.get(), dataset, false);
}

std::string FileReader::ReadStringValue(hid_t object,
                                        hid_t type,
                                        const std::string& where,
                                        bool attribute) const {
    const auto read = [&](hid_t memory, void* buffer) {
        const herr_t status = attribute
                                  ? H5Aread(object, memory, buffer)
                                  : H5Dread(object, memory, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer);
        if (status < 0) {
            throw Error(where, "", "cannot be read");
        }
    };
    if (H5Tis_variable_str(type) > 0) {
        // Variable-length strings live in the global heap: check it before HDF5 decodes it.
        CheckGlobalHeap(where, "variable-length string");
        const Id memory = Utf8StringType();
        char* text = nullptr;
        read(memory.get(), &text);
        std::string value;
        if (text != nullptr) {
            const std::size_t n = strnlen(text, kMaxStringBytes + 1);
            if (n > kMaxStringBytes) {
                H5free_memory(text);
                throw Error(
                    where, "more than " + std::to_string(kMaxStringBytes) + " bytes",
                    "string limit " + std::to_string(kMaxStringBytes) + ", see docs/limits.md");
            }
            value.assign(text, n);
        }
        H5free_memory(text);
        return value;
    }
    // Fixed-length string (casmap's own, or numpy bytes): read the bytes, drop NUL padding.
    const std::size_t size = H5Tget_size(type);
    if (size > kMaxStringBytes) {
        throw Error(where, std::to_string(size) + " bytes",
                    "string limit " + std::to_string(kMaxStringBytes) + ", see docs/limits.md");
    }
    std::string value(size, '\0');
    read(type, value.data());
    value.resize(std::min(value.find('\0'), value.size()));
    return value;
}

}  // namespace casmap::io::h5
