#include "casmap/pipeline/dataset_mpi.hpp"

#include <cstdlib>

#ifdef CASMAP_WITH_MPI
// The C API only: OpenMPI's mpi.h would otherwise pull in its deprecated C++ bindings.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>

#include <chrono>
#include <cstdio>
#include <map>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "casmap/io/atomic_file.hpp"
#endif

namespace casmap::pipeline {

bool LaunchedByMpi() {
#ifdef CASMAP_WITH_MPI
    return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMI_SIZE") != nullptr ||
           std::getenv("PMIX_RANK") != nullptr;
#else
    return false;
#endif
}

#ifndef CASMAP_WITH_MPI

bool DatasetMpiBuilt() { return false; }

DatasetSummary RunDatasetDistributed(const scenegen::DatasetSpec& spec,
                                     const DatasetContext& context,
                                     const DatasetOptions& options,
                                     DistributedRole& role) {
    role = {};
    return RunDataset(spec, context, options);
}

#else

bool DatasetMpiBuilt() { return true; }

namespace {

constexpr int kTagRequest = 1;  // worker -> 0: its last record (or none), asking for work
constexpr int kTagAssign = 2;   // 0 -> worker: the next index, or kStop
constexpr std::uint64_t kStop = ~std::uint64_t{0};

void Check(int code, const char* what) {
    if (code != MPI_SUCCESS) {
        throw std::runtime_error(std::string("MPI error in ") + what);
    }
}

// Records travel as "index ok reused\nline".
std::string Encode(const SampleRecord& r) {
    return std::to_string(r.index) + " " + (r.ok ? "1" : "0") + " " + (r.reused ? "1" : "0") +
           "\n" + r.line;
}

SampleRecord Decode(const std::string& text) {
    SampleRecord r;
    const std::size_t nl = text.find('\n');
    unsigned long long index = 0;
    int ok = 0;
    int reused = 0;
    std::sscanf(text.substr(0, nl).c_str(), "%llu %d %d", &index, &ok, &reused);
    r.index = static_cast<std::size_t>(index);
    r.ok = ok != 0;
    r.reused = reused != 0;
    r.line = text.substr(nl + 1);
    return r;
}

class MpiSession {
public:
    MpiSession() {
        int initialised = 0;
        MPI_Initialized(&initialised);
        if (initialised == 0) {
            int provided = 0;
            Check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided),
                  "MPI_Init_thread");
            owner_ = true;
        }
    }
    ~MpiSession() {
        if (owner_) {
            MPI_Finalize();
        }
    }
    MpiSession(const MpiSession&) = delete;
    MpiSession& operator=(const MpiSession&) = delete;

private:
    bool owner_ = false;
};

void Worker(const scenegen::DatasetSpec& spec, const DatasetContext& context) {
    std::string message;  // no record yet
    for (;;) {
        Check(MPI_Send(message.data(), static_cast<int>(message.size()), MPI_CHAR, 0, kTagRequest,
                       MPI_COMM_WORLD),
              "MPI_Send");
        std::uint64_t index = 0;
        Check(MPI_Recv(&index, 1, MPI_UINT64_T, 0, kTagAssign, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
              "MPI_Recv");
        if (index == kStop) {
            return;
        }
        message = Encode(ProduceSample(spec, context, static_cast<std::size_t>(index)));
    }
}

struct Scheduler {
    std::vector<std::size_t> indices;
    std::size_t next = 0;
    std::mutex mutex;
    std::map<std::size_t, SampleRecord> records;
    DatasetProgress progress;
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();

    std::uint64_t Take() {
        const std::lock_guard<std::mutex> lock(mutex);
        return next < indices.size() ? indices[next++] : kStop;
    }
    void Done(SampleRecord r, const DatasetOptions& options) {
        const std::lock_guard<std::mutex> lock(mutex);
        ++progress.done;
        progress.failed += r.ok ? 0 : 1;
        progress.elapsed_s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        records[r.index] = std::move(r);
        if (options.progress) {
            options.progress(progress);
        }
    }
};

// Rank 0's main thread: answers requests until every other rank got kStop.
void Dispatch(Scheduler& s, int ranks, const DatasetOptions& options) {
    int running = ranks - 1;
    std::string buffer;
    while (running > 0) {
        int flag = 0;
        MPI_Status status;
        Check(MPI_Iprobe(MPI_ANY_SOURCE, kTagRequest, MPI_COMM_WORLD, &flag, &status), "Iprobe");
        if (flag == 0) {
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
            continue;
        }
        int size = 0;
        MPI_Get_count(&status, MPI_CHAR, &size);
        buffer.assign(static_cast<std::size_t>(size), '\0');
        Check(MPI_Recv(buffer.data(), size, MPI_CHAR, status.MPI_SOURCE, kTagRequest,
                       MPI_COMM_WORLD, MPI_STATUS_IGNORE),
              "MPI_Recv");
        if (size > 0) {
            s.Done(Decode(buffer), options);
        }
        const std::uint64_t index = s.Take();
        Check(MPI_Send(&index, 1, MPI_UINT64_T, status.MPI_SOURCE, kTagAssign, MPI_COMM_WORLD),
              "MPI_Send");
        running -= index == kStop ? 1 : 0;
    }
}

}  // namespace

DatasetSummary RunDatasetDistributed(const scenegen::DatasetSpec& spec,
                                     const DatasetContext& context,
                                     const DatasetOptions& options,
                                     DistributedRole& role) {
    const MpiSession session;
    MPI_Comm_rank(MPI_COMM_WORLD, &role.rank);
    MPI_Comm_size(MPI_COMM_WORLD, &role.ranks);
    if (role.ranks == 1) {
        return RunDataset(spec, context, options);
    }
    if (role.rank != 0) {
        Worker(spec, context);
        MPI_Barrier(MPI_COMM_WORLD);
        return {};
    }
    io::EnsureDirectory(context.out_dir / "samples");
    Scheduler s;
    s.indices = ShardIndices(static_cast<std::size_t>(spec.count), options.shard, options.shards);
    s.progress.total = s.indices.size();
    std::vector<std::thread> local;
    for (int t = 0; t < std::max(1, options.threads); ++t) {
        local.emplace_back([&] {
            for (std::uint64_t i = s.Take(); i != kStop; i = s.Take()) {
                s.Done(ProduceSample(spec, context, static_cast<std::size_t>(i)), options);
            }
        });
    }
    Dispatch(s, role.ranks, options);
    for (std::thread& t : local) {
        t.join();
    }
    DatasetSummary summary = WriteDatasetIndex(spec, context.out_dir, s.records);
    summary.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - s.start).count();
    MPI_Barrier(MPI_COMM_WORLD);
    return summary;
}

#endif

}  // namespace casmap::pipeline
