#include "casmap/pipeline/bench_wire.hpp"

#include <cstring>
#include <stdexcept>
#include <type_traits>

namespace casmap::pipeline {
namespace {

class Writer {
public:
    template <typename T>
    void Put(T value) {
        static_assert(std::is_trivially_copyable_v<T>);
        char bytes[sizeof(T)];
        std::memcpy(bytes, &value, sizeof(T));
        out_.append(bytes, sizeof(T));
    }
    void Put(const std::string& s) {
        Put<std::uint64_t>(s.size());
        out_ += s;
    }
    void Put(const core::MapF& m) {
        Put<std::int32_t>(m.rows);
        Put<std::int32_t>(m.cols);
        out_.append(reinterpret_cast<const char*>(m.data.data()), m.data.size() * sizeof(float));
    }
    void Put(const mapper::ClassShares& s) {
        Put(s.cells);
        Put(s.removed_pct);
        Put(s.filled_pct);
        Put(s.untouched_pct);
    }
    void Put(const std::vector<std::string>& v) {
        Put<std::uint64_t>(v.size());
        for (const std::string& s : v) {
            Put(s);
        }
    }
    [[nodiscard]] std::string Take() { return std::move(out_); }

private:
    std::string out_;
};

class Reader {
public:
    explicit Reader(const std::string& in) : in_(in) {}
    template <typename T>
    T Get() {
        static_assert(std::is_trivially_copyable_v<T>);
        Need(sizeof(T));
        T value;
        std::memcpy(&value, in_.data() + at_, sizeof(T));
        at_ += sizeof(T);
        return value;
    }
    std::string String() {
        const auto n = static_cast<std::size_t>(Get<std::uint64_t>());
        Need(n);
        std::string s = in_.substr(at_, n);
        at_ += n;
        return s;
    }
    core::MapF Map() {
        core::MapF m;
        m.rows = Get<std::int32_t>();
        m.cols = Get<std::int32_t>();
        if (m.rows < 0 || m.cols < 0) {
            throw std::runtime_error("bench wire: negative map size");
        }
        const std::size_t n = static_cast<std::size_t>(m.rows) * static_cast<std::size_t>(m.cols);
        Need(n * sizeof(float));
        m.data.resize(n);
        if (n > 0) {  // an empty map has no buffer: memcpy must not see a null pointer
            std::memcpy(m.data.data(), in_.data() + at_, n * sizeof(float));
        }
        at_ += n * sizeof(float);
        return m;
    }
    mapper::ClassShares Shares() {
        mapper::ClassShares s;
        s.cells = Get<std::int64_t>();
        s.removed_pct = Get<double>();
        s.filled_pct = Get<double>();
        s.untouched_pct = Get<double>();
        return s;
    }
    std::vector<std::string> Strings() {
        std::vector<std::string> v(static_cast<std::size_t>(Get<std::uint64_t>()));
        for (std::string& s : v) {
            s = String();
        }
        return v;
    }
    [[nodiscard]] bool Done() const { return at_ == in_.size(); }

private:
    void Need(std::size_t n) const {
        if (in_.size() - at_ < n) {
            throw std::runtime_error("bench wire: truncated payload");
        }
    }
    const std::string& in_;
    std::size_t at_ = 0;
};

}  // namespace

std::string EncodeBenchRun(const BenchRunRecord& record) {
    Writer w;
    const BenchRun& r = record.run;
    w.Put<std::int32_t>(r.course);
    w.Put(r.test);
    w.Put(r.seed);
    w.Put<std::uint64_t>(r.filters.size());
    for (const auto& [name, s] : r.filters) {
        w.Put(name);
        w.Put(s.pi);
        w.Put(s.rmse_m);
        w.Put(s.spikes);
        w.Put(s.fill_error_m);
        w.Put(s.cells);
        w.Put(s.coverage);
        w.Put(s.edge_rmse_m);
        w.Put(s.open_rmse_m);
    }
    w.Put(r.cas_classes.all);
    w.Put(r.cas_classes.observed);
    w.Put(r.raw_rmse_m);
    w.Put(r.raw_spikes);
    w.Put(r.scans);
    w.Put(r.scene);
    w.Put(r.unknown);
    w.Put(r.poles);
    w.Put<std::uint64_t>(r.poles_kept.size());
    for (const auto& [name, kept] : r.poles_kept) {
        w.Put(name);
        w.Put(kept);
    }
    w.Put(record.name);
    w.Put(record.config_yaml);
    w.Put<std::uint8_t>(record.has_sheet ? 1 : 0);
    if (record.has_sheet) {
        const SheetMaps& s = record.sheet;
        w.Put(s.raw);
        w.Put(s.certainty);
        w.Put(s.truth);
        w.Put<std::uint64_t>(s.filtered.size());
        for (const auto& [name, map] : s.filtered) {
            w.Put(name);
            w.Put(map);
        }
        core::MapF classes(s.cas_classes.rows, s.cas_classes.cols);  // PixelClass as floats
        for (std::size_t i = 0; i < classes.data.size(); ++i) {
            classes.data[i] = static_cast<float>(s.cas_classes.data[i]);
        }
        w.Put(classes);
    }
    return w.Take();
}

BenchRunRecord DecodeBenchRun(const std::string& bytes) {
    Reader in(bytes);
    BenchRunRecord record;
    BenchRun& r = record.run;
    r.course = in.Get<std::int32_t>();
    r.test = in.String();
    r.seed = in.Get<std::uint64_t>();
    for (auto n = in.Get<std::uint64_t>(); n > 0; --n) {
        const std::string name = in.String();
        FilterScore& s = r.filters[name];
        s.pi = in.Get<double>();
        s.rmse_m = in.Get<double>();
        s.spikes = in.Get<std::int64_t>();
        s.fill_error_m = in.Get<double>();
        s.cells = in.Get<std::int64_t>();
        s.coverage = in.Get<double>();
        s.edge_rmse_m = in.Get<double>();
        s.open_rmse_m = in.Get<double>();
    }
    r.cas_classes.all = in.Shares();
    r.cas_classes.observed = in.Shares();
    r.raw_rmse_m = in.Get<double>();
    r.raw_spikes = in.Get<std::int64_t>();
    r.scans = in.Get<std::int64_t>();
    r.scene = in.String();
    r.unknown = in.String();
    r.poles = in.Strings();
    for (auto n = in.Get<std::uint64_t>(); n > 0; --n) {
        const std::string name = in.String();
        r.poles_kept[name] = in.Strings();
    }
    record.name = in.String();
    record.config_yaml = in.String();
    record.has_sheet = in.Get<std::uint8_t>() != 0;
    if (record.has_sheet) {
        SheetMaps& s = record.sheet;
        s.raw = in.Map();
        s.certainty = in.Map();
        s.truth = in.Map();
        for (auto n = in.Get<std::uint64_t>(); n > 0; --n) {
            const std::string name = in.String();
            s.filtered[name] = in.Map();
        }
        const core::MapF classes = in.Map();
        s.cas_classes = core::Raster<std::uint8_t>(classes.rows, classes.cols);
        for (std::size_t i = 0; i < classes.data.size(); ++i) {
            s.cas_classes.data[i] = static_cast<std::uint8_t>(classes.data[i]);
        }
    }
    if (!in.Done()) {
        throw std::runtime_error("bench wire: trailing bytes");
    }
    return record;
}

}  // namespace casmap::pipeline
