// One render spread over K processes (`mpirun -n K pathspace render ...`): which process this
// is, and the few collectives the renderer needs. The only interface to MPI: built without it,
// or run without a launcher, there is one process and every call is a no-op or the identity.
#pragma once
#include <cstdint>
#include <vector>

namespace ps::distributed {

// Starts MPI if this process was started by an MPI launcher (mpirun, srun, ...), else does
// nothing: a plain run stays a plain one-process program. Call once, first thing in main.
void start(int& argc, char**& argv);
// Ends MPI. With code != 0 in a job of several processes, aborts the whole job with that
// code (the others may be waiting in a collective); else finalizes. Returns code.
int finish(int code);

int rank();   // 0 .. size() - 1; 0 without MPI
int size();   // 1 without MPI
inline bool isRoot() { return rank() == 0; }

// Every process waits for the others (aligns the render clocks).
void barrier();
// True on every process if `local` is true on any; every process must call it. At a pass
// boundary: whether to stop (a time limit, the clocks having started together, or a signal
// that reached any process), so that all stop together.
bool anyOf(bool local);

// Sums over processes into rank 0's vector (same length on every process; the others'
// are left unspecified). Integer sums, so the result does not depend on the order.
void sumToRoot(std::vector<int64_t>& v);
void sumToRoot(std::vector<__int128>& v);
// Bitwise OR over processes into rank 0's vector (same length everywhere; others' left
// unspecified): which samples any process took.
void orToRoot(std::vector<uint64_t>& v);
// Rank 0's values on every process (same length everywhere).
void broadcastFromRoot(std::vector<int64_t>& v);
void broadcastFromRoot(std::vector<uint64_t>& v);
// Every process gets every entry, bit for bit, where each entry is set by at most one
// process and is zero (all bits) on the others: a bitwise OR over processes, so no
// rounding and no order. For results computed in disjoint parts (a Metropolis bootstrap's
// samples, split over the processes), which every process then needs whole.
void mergeDisjoint(std::vector<uint64_t>& v);
void mergeDisjoint(std::vector<double>& v);
// Every process's value, in rank order, on rank 0 (elsewhere: empty).
std::vector<double> gatherToRoot(double x);

// What the sums above moved and how long they took, over the whole run (this process).
struct Traffic {
    double bytes = 0;    // payload bytes this process contributed
    double seconds = 0;  // time spent inside the reductions
};
Traffic traffic();

}  // namespace ps::distributed
