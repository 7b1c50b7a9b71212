// One render spread over K processes (`mpirun -n K pathspace render ...`): which process this
// is, and the few collectives the renderer needs. The only interface to MPI: built without it,
// or run without a launcher, there is one process and every call is a no-op or the identity.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "util/error.h"

namespace ps::distributed {

// Starts MPI if this process was started by an MPI launcher (mpirun, srun, ...), else does
// nothing: a plain run stays a plain one-process program. Call once, first thing in main.
void start(int& argc, char**& argv);
// Ends MPI. With code != 0 in a job of several processes, aborts the whole job with that
// code (the others may be waiting in a collective), unless every process ends with it
// `together` (a JobInputError): then, as on success, finalizes. Returns code.
int finish(int code, bool together = false);

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
// The largest of the processes' values, on every process.
int64_t maxOf(int64_t x);
// Every process's bytes, concatenated in rank order, on rank 0 (elsewhere: empty).
std::vector<char> gatherBytesToRoot(const std::vector<char>& bytes);
// Rank 0's bytes on every process (any length: the others' vectors are resized).
void broadcastBytes(std::vector<char>& bytes);

// The lowest rank for which `local` is set gives `message` (its own) to every process, which
// all return it; "" when no process has one. Every process must call it: a refusal that one
// process meets during a render becomes every process's, at the same point, so that all stop
// together (no process left waiting in a collective) and rank 0 reports it once.
std::string firstMessage(bool local, const std::string& message);

// A refusal every process raised together (refuseTogether): rank 0 reports it, the others
// stay silent, and the job ends with its status without an abort.
class JobInputError : public InputError {
public:
    using InputError::InputError;
};
// Every process calls it at the same point; if `local` is set on any, all throw
// JobInputError with the lowest such rank's `message`.
void refuseTogether(bool local, const std::string& message);

// Every process calls it at a point all reach before the render (after the command line, after
// loading the scene), `local` saying whether this process failed there with `message` (an
// input error). Returns false if none failed, true if every process did (the same files and
// options give every process the same error: each then ends as after a JobInputError, rank 0
// reporting its own message). If only some failed, the processes read different inputs (a
// file readable on one machine only): that is no refusal of the job's settings but a fault of
// a machine, which the job cannot go on without, so rank 0 reports the lowest failing rank's
// message (with its rank) and aborts the job with `code` (mpirun adds its note of the abort),
// the others waiting for it: it does not return.
bool failedEverywhere(bool local, const std::string& message, int code);

// What every collective above moved and how long it took, over the whole run (this process):
// in all and by purpose (the label in force when it ran, see Purpose).
struct Traffic {
    double bytes = 0;    // payload bytes this process contributed (sent, or received from rank 0)
    double seconds = 0;  // time spent inside the collectives (waits for the others included)
};
Traffic traffic();
std::map<std::string, Traffic> trafficByPurpose();
// While one lives, the collectives this process runs count under `name` ("film", "stop
// decisions", ...); the outermost label wins, so a helper's own label does not split a
// caller's purpose. Without one they count under "other".
class Purpose {
public:
    explicit Purpose(const char* name);
    ~Purpose();
    Purpose(const Purpose&) = delete;
    Purpose& operator=(const Purpose&) = delete;

private:
    const char* previous_;
};

}  // namespace ps::distributed
