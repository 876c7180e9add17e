#include "casmap/pipeline/distributed.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <mutex>
#include <thread>

#ifdef CASMAP_WITH_MPI
// The C API only: OpenMPI's mpi.h would otherwise pull in its deprecated C++ bindings.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>

#include <chrono>
#include <stdexcept>
#endif

namespace casmap::pipeline {
namespace {

constexpr std::uint64_t kStop = ~std::uint64_t{0};

// The items not handed out yet and the payloads collected so far (rank 0).
struct Queue {
    const std::vector<std::size_t>* items = nullptr;
    std::size_t next = 0;
    std::map<std::size_t, std::string> payloads;
    const DoneFn* done = nullptr;
    std::mutex mutex;

    std::uint64_t Take() {
        const std::lock_guard<std::mutex> lock(mutex);
        return next < items->size() ? (*items)[next++] : kStop;
    }
    void Finish(std::size_t item, std::string payload) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (*done) {
            (*done)(item, payload);
        }
        payloads[item] = std::move(payload);
    }
};

std::vector<std::thread> StartLocalWorkers(Queue& queue, int threads, const WorkFn& work) {
    std::vector<std::thread> pool;
    for (int t = 0; t < std::max(1, threads); ++t) {
        pool.emplace_back([&queue, &work] {
            for (std::uint64_t i = queue.Take(); i != kStop; i = queue.Take()) {
                queue.Finish(static_cast<std::size_t>(i), work(static_cast<std::size_t>(i)));
            }
        });
    }
    return pool;
}

#ifdef CASMAP_WITH_MPI
constexpr int kTagRequest = 1;  // rank -> 0: "item\npayload" of its last item, or empty
constexpr int kTagAssign = 2;   // 0 -> rank: the next item, or kStop

void Check(int code, const char* what) {
    if (code != MPI_SUCCESS) {
        throw std::runtime_error(std::string("MPI error in ") + what);
    }
}

void Worker(const WorkFn& work) {
    std::string message;
    for (;;) {
        Check(MPI_Send(message.data(), static_cast<int>(message.size()), MPI_CHAR, 0, kTagRequest,
                       MPI_COMM_WORLD),
              "MPI_Send");
        std::uint64_t item = 0;
        Check(MPI_Recv(&item, 1, MPI_UINT64_T, 0, kTagAssign, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
              "MPI_Recv");
        if (item == kStop) {
            return;
        }
        message = std::to_string(item) + "\n" + work(static_cast<std::size_t>(item));
    }
}

// Rank 0's main thread: answers requests until every other rank got kStop.
void Schedule(Queue& queue, int ranks) {
    int running = ranks - 1;
    std::string buffer;
    while (running > 0) {
        int flag = 0;
        MPI_Status status;
        Check(MPI_Iprobe(MPI_ANY_SOURCE, kTagRequest, MPI_COMM_WORLD, &flag, &status),
              "MPI_Iprobe");
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
            const std::size_t nl = buffer.find('\n');
            queue.Finish(static_cast<std::size_t>(std::stoull(buffer.substr(0, nl))),
                         buffer.substr(nl + 1));
        }
        const std::uint64_t item = queue.Take();
        Check(MPI_Send(&item, 1, MPI_UINT64_T, status.MPI_SOURCE, kTagAssign, MPI_COMM_WORLD),
              "MPI_Send");
        running -= item == kStop ? 1 : 0;
    }
}
#endif

}  // namespace

bool MpiBuilt() {
#ifdef CASMAP_WITH_MPI
    return true;
#else
    return false;
#endif
}

bool LaunchedByMpi() {
    return MpiBuilt() &&
           (std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMI_SIZE") != nullptr ||
            std::getenv("PMIX_RANK") != nullptr);
}

DistributedSession::DistributedSession() {
#ifdef CASMAP_WITH_MPI
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (initialised == 0 && !LaunchedByMpi()) {
        return;
    }
    if (initialised == 0) {
        int provided = 0;
        Check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init");
        owner_ = true;
    }
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks_);
#endif
}

DistributedSession DistributedSession::Local() { return DistributedSession(LocalTag{}); }

DistributedSession::~DistributedSession() {
#ifdef CASMAP_WITH_MPI
    if (owner_) {
        MPI_Finalize();
    }
#endif
}

void DistributedSession::Barrier() const {
#ifdef CASMAP_WITH_MPI
    if (ranks_ > 1) {
        MPI_Barrier(MPI_COMM_WORLD);
    }
#endif
}

std::string DistributedSession::Broadcast(std::string text) const {
#ifdef CASMAP_WITH_MPI
    if (ranks_ > 1) {
        std::uint64_t size = text.size();
        Check(MPI_Bcast(&size, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD), "MPI_Bcast");
        text.resize(static_cast<std::size_t>(size));
        constexpr std::uint64_t kChunk = 1U << 30;
        for (std::uint64_t at = 0; at < size; at += kChunk) {
            const int n = static_cast<int>(std::min(kChunk, size - at));
            Check(MPI_Bcast(text.data() + at, n, MPI_CHAR, 0, MPI_COMM_WORLD), "MPI_Bcast");
        }
    }
#endif
    return text;
}

std::map<std::size_t, std::string> DistributeWork(const DistributedSession& session,
                                                  const std::vector<std::size_t>& items,
                                                  int threads,
                                                  const WorkFn& work,
                                                  const DoneFn& done) {
    Queue queue;
    queue.items = &items;
    queue.done = &done;
#ifdef CASMAP_WITH_MPI
    if (session.ranks() > 1 && session.rank() != 0) {
        Worker(work);
        return {};
    }
#endif
    std::vector<std::thread> pool = StartLocalWorkers(queue, threads, work);
#ifdef CASMAP_WITH_MPI
    if (session.ranks() > 1) {
        Schedule(queue, session.ranks());
    }
#else
    (void)session;
#endif
    for (std::thread& t : pool) {
        t.join();
    }
    return std::move(queue.payloads);
}

}  // namespace casmap::pipeline
