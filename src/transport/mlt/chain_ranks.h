// Markov-chain renders over several processes (render/distributed.h; thesis ch. 11's chains
// are independent given the bootstrap, so they split like samples):
//  - the bootstrap's samples are split by blocks over the processes, and every process gets
//    every sample's weight (each computed by one process from its own stream, merged bit for
//    bit), then sums them in index order: all hold one process's b, strategy choice and
//    candidate initial states, and time the bootstrap 1/K of one process's;
//  - chain c runs on process c mod K, from its own streams (keyed by the seed and c), with
//    its share of the mutations, so it makes the same mutations as in one process;
//  - the splat films' fixed-point sums add up on rank 0 to one process's film, and the image
//    is normalised by the mutations of all processes (on an early stop too: they agree after
//    every pass of mutations whether to stop).
// So the image is one process's, bit for bit, for any number of processes and threads.
#pragma once
#include <bit>
#include <cstdint>
#include <vector>

#include "render/distributed.h"
#include "transport/renderer.h"

namespace ps::chain_ranks {

// Whether this process runs chain c / takes bootstrap block b.
inline bool ownsChain(int c) { return c % distributed::size() == distributed::rank(); }
inline bool ownsBlock(int64_t b) { return b % distributed::size() == distributed::rank(); }

// The chains this process runs, in order, and *mutations their share of `total` mutations
// over `chains` chains (chain c makes total / chains, one more for the first total % chains).
inline long long chainMutations(long long total, int chains, int c) { return total / chains + (c < total % chains ? 1 : 0); }
inline std::vector<int> ownedChains(int chains, long long total, long long* mutations) {
    std::vector<int> mine;
    *mutations = 0;
    for (int c = 0; c < chains; ++c)
        if (ownsChain(c)) {
            mine.push_back(c);
            *mutations += chainMutations(total, chains, c);
        }
    return mine;
}

// Per chain, a record of `stride` 64-bit words (counts and sums), filled by the process
// that runs the chain (zero elsewhere); gathered, rank 0 holds every chain's, bit for bit,
// and sums them in chain order as one process would.
class ChainRecords {
public:
    ChainRecords(int chains, size_t stride) : stride_(stride), words_(size_t(chains) * stride, 0) {}
    void put(int c, size_t k, long long v) { words_[size_t(c) * stride_ + k] = uint64_t(v); }
    void put(int c, size_t k, double v) { words_[size_t(c) * stride_ + k] = std::bit_cast<uint64_t>(v); }
    long long count(int c, size_t k) const { return (long long)words_[size_t(c) * stride_ + k]; }
    double real(int c, size_t k) const { return std::bit_cast<double>(words_[size_t(c) * stride_ + k]); }
    void gatherToRoot() { distributed::orToRoot(words_); }

private:
    size_t stride_;
    std::vector<uint64_t> words_;
};

// ms.rankMutations and ms.rankAcceptance from each chain's mutations, acceptances and
// proposals (chain c ran on process c mod K).
void perProcess(MetropolisStats& ms, const std::vector<long long>& done, const std::vector<long long>& accepted,
                const std::vector<long long>& proposed);

}  // namespace ps::chain_ranks
