#include "render/distributed.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

#if PATHSPACE_HAVE_MPI
#include <mpi.h>
#endif

namespace ps::distributed {

namespace {

Traffic gTraffic;
std::map<std::string, Traffic> gByPurpose;
const char* gPurpose = nullptr;  // only the main thread runs collectives

#if PATHSPACE_HAVE_MPI
// Times one collective and counts its payload, in all and under the purpose in force.
struct Timed {
    explicit Timed(double bytes) : start(std::chrono::steady_clock::now()), purpose(gPurpose ? gPurpose : "other") {
        add(bytes);
    }
    void add(double bytes) {
        gTraffic.bytes += bytes;
        gByPurpose[purpose].bytes += bytes;
    }
    ~Timed() {
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        gTraffic.seconds += s;
        gByPurpose[purpose].seconds += s;
    }
    std::chrono::steady_clock::time_point start;
    const char* purpose;
};

bool gStarted = false;
int gRank = 0, gSize = 1;
MPI_Datatype gInt128 = MPI_DATATYPE_NULL;
MPI_Op gSumInt128 = MPI_OP_NULL;

// MPI has no 128-bit integer: a 16-byte type and its sum as a user operation.
void sumInt128(void* in, void* inout, int* len, MPI_Datatype*) {
    const auto* a = static_cast<const unsigned char*>(in);
    auto* b = static_cast<unsigned char*>(inout);
    for (int i = 0; i < *len; ++i) {
        __int128 x, y;
        std::memcpy(&x, a + 16 * size_t(i), 16);
        std::memcpy(&y, b + 16 * size_t(i), 16);
        y += x;
        std::memcpy(b + 16 * size_t(i), &y, 16);
    }
}

// Launched by mpirun/mpiexec (Open MPI, MPICH/Hydra) or a PMI/PMIx scheduler such as srun.
bool launchedByMpi() {
    for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
        if (std::getenv(v)) return true;
    return false;
}

void check(int err, const char* what) {
    if (err == MPI_SUCCESS) return;
    char text[MPI_MAX_ERROR_STRING];
    int n = 0;
    MPI_Error_string(err, text, &n);
    throw std::runtime_error(std::string("MPI ") + what + ": " + std::string(text, size_t(n)));
}

// Collectives go in chunks of 2^14 elements (256 KB of 128-bit sums): MPI's temporary
// buffers then stay small and are reused, where one buffer of a whole film is new memory to
// fault in at every reduction (bench/README: 2 processes, a 1024x1024 film, 0.83 s in one
// piece, 0.033 s in chunks); and no count exceeds an int.
template <class F>
void inChunks(size_t n, F f) {
    constexpr size_t kChunk = size_t(1) << 14;
    for (size_t i = 0; i < n; i += kChunk) f(i, int(std::min(kChunk, n - i)));
}
#endif

}  // namespace

void start(int& argc, char**& argv) {
#if PATHSPACE_HAVE_MPI
    if (gStarted || !launchedByMpi()) return;
    // Only the main thread calls MPI (at pass boundaries); the render threads never do.
    int provided = 0;
    check(MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided), "init");
    gStarted = true;
    MPI_Comm_rank(MPI_COMM_WORLD, &gRank);
    MPI_Comm_size(MPI_COMM_WORLD, &gSize);
    // Errors come back as codes (turned into exceptions), not as an abort inside MPI.
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
    MPI_Type_contiguous(16, MPI_BYTE, &gInt128);
    MPI_Type_commit(&gInt128);
    MPI_Op_create(&sumInt128, 1, &gSumInt128);
#else
    (void)argc;
    (void)argv;
#endif
}

int finish(int code, bool together) {
#if PATHSPACE_HAVE_MPI
    if (!gStarted) return code;
    if (code != 0 && code != 130 && gSize > 1 && !together) MPI_Abort(MPI_COMM_WORLD, code);
    MPI_Op_free(&gSumInt128);
    MPI_Type_free(&gInt128);
    MPI_Finalize();
    gStarted = false;
#endif
    return code;
}

int rank() {
#if PATHSPACE_HAVE_MPI
    return gRank;
#else
    return 0;
#endif
}

int size() {
#if PATHSPACE_HAVE_MPI
    return gSize;
#else
    return 1;
#endif
}

void barrier() {
#if PATHSPACE_HAVE_MPI
    if (gSize > 1) check(MPI_Barrier(MPI_COMM_WORLD), "barrier");
#endif
}

bool anyOf(bool local) {
#if PATHSPACE_HAVE_MPI
    if (gSize > 1) {
        int in = local ? 1 : 0, out = 0;
        Timed t(sizeof in);
        check(MPI_Allreduce(&in, &out, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD), "stop decision");
        return out != 0;
    }
#endif
    return local;
}

void sumToRoot(std::vector<int64_t>& v) {
#if PATHSPACE_HAVE_MPI
    if (gSize <= 1) return;
    Timed t(double(v.size() * sizeof(int64_t)));
    inChunks(v.size(), [&](size_t at, int n) {
        void* send = gRank == 0 ? MPI_IN_PLACE : v.data() + at;
        check(MPI_Reduce(send, v.data() + at, n, MPI_INT64_T, MPI_SUM, 0, MPI_COMM_WORLD), "reduce");
    });
#else
    (void)v;
#endif
}

void sumToRoot(std::vector<__int128>& v) {
#if PATHSPACE_HAVE_MPI
    if (gSize <= 1) return;
    Timed t(double(v.size() * sizeof(__int128)));
    inChunks(v.size(), [&](size_t at, int n) {
        void* send = gRank == 0 ? MPI_IN_PLACE : v.data() + at;
        check(MPI_Reduce(send, v.data() + at, n, gInt128, gSumInt128, 0, MPI_COMM_WORLD), "reduce");
    });
#else
    (void)v;
#endif
}

void orToRoot(std::vector<uint64_t>& v) {
#if PATHSPACE_HAVE_MPI
    if (gSize <= 1) return;
    Timed t(double(v.size() * sizeof(uint64_t)));
    inChunks(v.size(), [&](size_t at, int n) {
        void* send = gRank == 0 ? MPI_IN_PLACE : v.data() + at;
        check(MPI_Reduce(send, v.data() + at, n, MPI_UINT64_T, MPI_BOR, 0, MPI_COMM_WORLD), "reduce");
    });
#else
    (void)v;
#endif
}

void broadcastFromRoot(std::vector<int64_t>& v) {
#if PATHSPACE_HAVE_MPI
    if (gSize <= 1) return;
    Timed t(double(v.size() * sizeof(int64_t)));
    inChunks(v.size(), [&](size_t at, int n) {
        check(MPI_Bcast(v.data() + at, n, MPI_INT64_T, 0, MPI_COMM_WORLD), "broadcast");
    });
#else
    (void)v;
#endif
}

void broadcastFromRoot(std::vector<uint64_t>& v) {
#if PATHSPACE_HAVE_MPI
    if (gSize <= 1) return;
    Timed t(double(v.size() * sizeof(uint64_t)));
    inChunks(v.size(), [&](size_t at, int n) {
        check(MPI_Bcast(v.data() + at, n, MPI_UINT64_T, 0, MPI_COMM_WORLD), "broadcast");
    });
#else
    (void)v;
#endif
}

void mergeDisjoint(std::vector<uint64_t>& v) {
#if PATHSPACE_HAVE_MPI
    if (gSize <= 1) return;
    Timed t(double(v.size() * sizeof(uint64_t)));
    inChunks(v.size(), [&](size_t at, int n) {
        check(MPI_Allreduce(MPI_IN_PLACE, v.data() + at, n, MPI_UINT64_T, MPI_BOR, MPI_COMM_WORLD), "merge");
    });
#else
    (void)v;
#endif
}

void mergeDisjoint(std::vector<double>& v) {
    static_assert(sizeof(double) == sizeof(uint64_t));
    if (size() <= 1 || v.empty()) return;
    std::vector<uint64_t> bits(v.size());
    std::memcpy(bits.data(), v.data(), v.size() * sizeof(double));
    mergeDisjoint(bits);
    std::memcpy(v.data(), bits.data(), v.size() * sizeof(double));
}

std::vector<double> gatherToRoot(double x) {
#if PATHSPACE_HAVE_MPI
    if (gSize > 1) {
        std::vector<double> all(gRank == 0 ? size_t(gSize) : 0);
        Timed t(sizeof x);
        check(MPI_Gather(&x, 1, MPI_DOUBLE, all.data(), 1, MPI_DOUBLE, 0, MPI_COMM_WORLD), "gather");
        return all;
    }
#endif
    return {x};
}

int64_t maxOf(int64_t x) {
#if PATHSPACE_HAVE_MPI
    if (gSize > 1) {
        int64_t out = 0;
        Timed t(sizeof x);
        check(MPI_Allreduce(&x, &out, 1, MPI_INT64_T, MPI_MAX, MPI_COMM_WORLD), "maximum");
        return out;
    }
#endif
    return x;
}

std::vector<char> gatherBytesToRoot(const std::vector<char>& bytes) {
#if PATHSPACE_HAVE_MPI
    if (gSize > 1) {
        // The sizes first (each process's share may exceed an int: sent in chunks of bytes).
        const int64_t mine = int64_t(bytes.size());
        std::vector<int64_t> sizes(gRank == 0 ? size_t(gSize) : 0);
        Timed t(double(sizeof mine + bytes.size()));
        check(MPI_Gather(&mine, 1, MPI_INT64_T, sizes.data(), 1, MPI_INT64_T, 0, MPI_COMM_WORLD), "gather");
        std::vector<char> all;
        if (gRank != 0) {
            inChunks(bytes.size(), [&](size_t at, int n) {
                check(MPI_Send(bytes.data() + at, n, MPI_BYTE, 0, 0, MPI_COMM_WORLD), "send");
            });
            return all;
        }
        all = bytes;
        for (int r = 1; r < gSize; ++r) {
            const size_t from = all.size();
            all.resize(from + size_t(sizes[size_t(r)]));
            inChunks(size_t(sizes[size_t(r)]), [&](size_t at, int n) {
                check(MPI_Recv(all.data() + from + at, n, MPI_BYTE, r, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "receive");
            });
        }
        return all;
    }
#endif
    return bytes;
}

void broadcastBytes(std::vector<char>& bytes) {
#if PATHSPACE_HAVE_MPI
    if (gSize <= 1) return;
    int64_t n = int64_t(bytes.size());
    Timed t(double(sizeof n));
    check(MPI_Bcast(&n, 1, MPI_INT64_T, 0, MPI_COMM_WORLD), "broadcast");
    bytes.resize(size_t(n));
    t.add(double(n));
    inChunks(bytes.size(), [&](size_t at, int k) {
        check(MPI_Bcast(bytes.data() + at, k, MPI_BYTE, 0, MPI_COMM_WORLD), "broadcast");
    });
#else
    (void)bytes;
#endif
}

#if PATHSPACE_HAVE_MPI
namespace {
// Rank `from`'s message on every process.
std::string messageFrom(int from, const std::string& message) {
    int64_t n = int64_t(message.size());
    Timed t(double(sizeof n));
    check(MPI_Bcast(&n, 1, MPI_INT64_T, from, MPI_COMM_WORLD), "broadcast");
    t.add(double(n));
    std::string text = gRank == from ? message : std::string(size_t(n), '\0');
    check(MPI_Bcast(text.data(), int(n), MPI_CHAR, from, MPI_COMM_WORLD), "broadcast");
    return text;
}
}  // namespace
#endif

std::string firstMessage(bool local, const std::string& message) {
#if PATHSPACE_HAVE_MPI
    if (gSize > 1) {
        int mine = local ? gRank : gSize, first = gSize;
        {
            Timed t(sizeof mine);
            check(MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD), "error decision");
        }
        return first == gSize ? "" : messageFrom(first, message);
    }
#endif
    return local ? message : "";
}

bool failedEverywhere(bool local, const std::string& message, int code) {
#if PATHSPACE_HAVE_MPI
    if (gSize > 1) {
        Purpose purpose("error decisions");
        // One minimum over both: the lowest failing rank (gSize if none), and 1 only if every
        // process failed.
        int mine[2] = {local ? gRank : gSize, local ? 1 : 0}, all[2] = {gSize, 0};
        {
            Timed t(sizeof mine);
            check(MPI_Allreduce(mine, all, 2, MPI_INT, MPI_MIN, MPI_COMM_WORLD), "input check");
        }
        if (all[0] == gSize) return false;
        if (all[1] == 1) return true;
        const int first = all[0];
        const std::string text = messageFrom(first, message);
        if (gRank == 0) {
            const std::string where = first != 0 ? "rank " + std::to_string(first) + ": " : "";
            std::fprintf(stderr, "%s%s\n", where.c_str(), printableMessage(text).c_str());
            std::fflush(stderr);
            MPI_Abort(MPI_COMM_WORLD, code);
        }
        // Rank 0 never joins: this waits for its abort, which ends this process.
        MPI_Barrier(MPI_COMM_WORLD);
        std::_Exit(code);
    }
#else
    (void)message;
    (void)code;
#endif
    return local;
}

void refuseTogether(bool local, const std::string& message) {
    Purpose purpose("error decisions");
    const std::string text = firstMessage(local, message);
    if (!text.empty()) throw JobInputError(text);
}

Traffic traffic() { return gTraffic; }
std::map<std::string, Traffic> trafficByPurpose() { return gByPurpose; }

Purpose::Purpose(const char* name) : previous_(gPurpose) {
    if (!gPurpose) gPurpose = name;
}
Purpose::~Purpose() { gPurpose = previous_; }

}  // namespace ps::distributed
