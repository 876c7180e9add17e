#include "casmap/pipeline/sweep_payload.hpp"

#include <cstring>
#include <stdexcept>
#include <utility>

namespace casmap::pipeline::detail {

void PutU64(std::string& out, std::uint64_t v) {
    char b[8];
    std::memcpy(b, &v, 8);
    out.append(b, 8);
}

void PutF64(std::string& out, double v) {
    std::uint64_t u = 0;
    std::memcpy(&u, &v, 8);
    PutU64(out, u);
}

void PutStr(std::string& out, const std::string& s) {
    PutU64(out, s.size());
    out += s;
}

std::uint64_t Reader::U64() {
    if (at + 8 > in.size()) {
        throw std::runtime_error("sweep payload truncated");
    }
    std::uint64_t v = 0;
    std::memcpy(&v, in.data() + at, 8);
    at += 8;
    return v;
}

double Reader::F64() {
    const std::uint64_t u = U64();
    double v = 0.0;
    std::memcpy(&v, &u, 8);
    return v;
}

std::string Reader::Str() {
    const std::size_t n = static_cast<std::size_t>(U64());
    if (at + n > in.size()) {
        throw std::runtime_error("sweep payload truncated");
    }
    std::string s = in.substr(at, n);
    at += n;
    return s;
}

void PutScore(std::string& out, const CasScore& s) {
    PutF64(out, s.pi);
    PutF64(out, s.classes.all.removed_pct);
    PutF64(out, s.classes.all.filled_pct);
    PutF64(out, s.classes.all.untouched_pct);
    PutU64(out, static_cast<std::uint64_t>(s.spikes));
    PutU64(out, s.poles);
    PutU64(out, s.poles_kept);
}

CasScore GetScore(Reader& r) {
    CasScore s;
    s.pi = r.F64();
    s.classes.all.removed_pct = r.F64();
    s.classes.all.filled_pct = r.F64();
    s.classes.all.untouched_pct = r.F64();
    s.spikes = static_cast<std::int64_t>(r.U64());
    s.poles = static_cast<std::size_t>(r.U64());
    s.poles_kept = static_cast<std::size_t>(r.U64());
    return s;
}

std::vector<std::string> Gather(const DistributedSession& session,
                                const std::map<std::size_t, std::string>& payloads,
                                std::size_t count) {
    std::string all;
    if (session.rank() == 0) {
        for (const auto& [item, payload] : payloads) {
            PutU64(all, item);
            PutStr(all, payload);
        }
    }
    all = session.Broadcast(std::move(all));
    std::vector<std::string> out(count);
    Reader r{all};
    while (r.at < all.size()) {
        const std::size_t item = static_cast<std::size_t>(r.U64());
        out.at(item) = r.Str();
    }
    for (const std::string& p : out) {
        if (p.empty()) {
            throw std::runtime_error("sweep: a run sent no result");
        }
        if (p.front() == 'E') {
            throw std::runtime_error(p.substr(1));
        }
    }
    return out;
}

}  // namespace casmap::pipeline::detail
