// Checkpoints of Markov-chain renders (pssmlt, mmlt, mlt; transport/checkpoint.h holds the
// file). The chains advance in passes; between two passes every chain is between two of
// its own mutations, so its whole state (its current sample or path, its random streams,
// its counters and its mutations left) and the film's exact sums are a point from which the
// render goes on as if never stopped. A checkpoint holds them with what the chains need of
// the bootstrap (b, the strategy choice, ...), so a resumed render runs no bootstrap.
// Chain c's state does not depend on the processes (chain_ranks.h): rank 0 gathers every
// chain's, stores them in chain order, and a resumed render on any number of processes
// takes each chain where it stood, to the image of one uninterrupted run, bit for bit.
// A render stopped within a pass (a signal, --time) leaves each chain at its own boundary
// (a chain does a pass's mutations whole or not at all), so its last checkpoint is exact too.
#pragma once
#include <chrono>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "film/film.h"
#include "transport/checkpoint.h"
#include "transport/renderer.h"
#include "util/byte_stream.h"

namespace ps {

class ChainCheckpoints {
public:
    // Every process constructs it at the same point: with options.resume, rank 0's chain
    // states reach every process (a collective) and are checked against `chains` (InputError
    // before anything is rendered). `total`: the render's mutations over all chains.
    ChainCheckpoints(const RenderOptions& options, int chains, long long total);

    bool resuming() const { return resume_ != nullptr; }
    // The resumed render's bootstrap results and chain c's state (resuming() only).
    ByteReader bootstrap() const { return reader(bootstrap_, "the bootstrap"); }
    ByteReader chain(int c) const { return reader(chains_[size_t(c)], "chain " + std::to_string(c)); }
    const CheckpointState* resume() const { return resume_; }
    // The mutations a resumed chain c gains when the resume raises --spp: a chain's course
    // does not depend on how many mutations it is to make, so the chains, continued to their
    // new share, make the uninterrupted render of the new --spp.
    long long addedMutations(int c) const;

    // After a pass: whether a checkpoint is due (--checkpoint-every seconds since the last;
    // every process agrees), or, with `stopped`, whether the render stopping early is to
    // write its last one.
    bool due(bool stopped);
    // Writes one on rank 0: every process's film sums and the resumed render's, the path
    // statistics and this run's mutations of every process plus the resumed ones, and every
    // chain's state (saveChain(c, out) for the chains this process runs) after `bootstrap`.
    void write(const Film& film, const std::vector<char>& bootstrap, const std::vector<int>& mine,
               const std::function<void(int, ByteWriter&)>& saveChain, long long mutationsThisRun,
               const PathStats& stats, RenderResult& result);

private:
    ByteReader reader(std::span<const char> s, const std::string& what) const;

    const RenderOptions& options_;
    const CheckpointState* resume_;
    int chains_count_;
    long long total_;
    std::vector<char> blob_;  // the resumed state, on every process
    std::span<const char> bootstrap_;
    std::vector<std::span<const char>> chains_;
    std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

}  // namespace ps
