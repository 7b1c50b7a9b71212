#include "transport/mlt/chain_checkpoint.h"

#include <stdexcept>

#include "render/distributed.h"
#include "transport/film_reduction.h"
#include "transport/mlt/chain_ranks.h"

namespace ps {

namespace {

// The chains' section: a tag, the chain count, the bootstrap's bytes, then each chain's
// bytes in chain order (each with its size).
constexpr uint32_t kTag = 0x4e494843;  // "CHIN"

}  // namespace

ChainCheckpoints::ChainCheckpoints(const RenderOptions& options, int chains, long long total)
    : options_(options), resume_(options.resume), chains_count_(chains), total_(total) {
    if (!resume_) return;
    distributed::Purpose purpose("checkpoint");
    if (distributed::isRoot()) blob_ = resume_->chains;
    distributed::broadcastBytes(blob_);
    const std::string what = "--resume: the checkpoint's chains";
    if (blob_.empty()) throw InputError(what + ": there are none (not a Metropolis render's checkpoint)");
    ByteReader in(blob_, what);
    if (in.get<uint32_t>() != kTag) in.fail();
    const uint32_t n = in.get<uint32_t>();
    if (n != uint32_t(chains))
        throw InputError(what + ": " + std::to_string(n) + " chains, this render has " + std::to_string(chains));
    bootstrap_ = in.getSpan(size_t(in.get<uint64_t>()));
    for (uint32_t c = 0; c < n; ++c) chains_.push_back(in.getSpan(size_t(in.get<uint64_t>())));
    if (!in.atEnd()) in.fail();
}

ByteReader ChainCheckpoints::reader(std::span<const char> s, const std::string& what) const {
    return ByteReader(s, "--resume: the checkpoint's state of " + what);
}

long long ChainCheckpoints::addedMutations(int c) const {
    if (!resume_ || resume_->spp <= 0 || resume_->spp >= options_.spp) return 0;
    const long long before = total_ / options_.spp * resume_->spp;
    return chain_ranks::chainMutations(total_, chains_count_, c) - chain_ranks::chainMutations(before, chains_count_, c);
}

bool ChainCheckpoints::due(bool stopped) {
    if (options_.checkpointEvery < 0 || !options_.checkpoint) return false;
    if (stopped) return true;  // every process stopped together
    const double since = std::chrono::duration<double>(std::chrono::steady_clock::now() - last_).count();
    distributed::Purpose purpose("checkpoint");
    return distributed::anyOf(since >= options_.checkpointEvery);
}

void ChainCheckpoints::write(const Film& film, const std::vector<char>& bootstrap, const std::vector<int>& mine,
                             const std::function<void(int, ByteWriter&)>& saveChain, long long mutationsThisRun,
                             const PathStats& stats, RenderResult& result) {
    distributed::Purpose purpose("checkpoint");
    CheckpointState state;
    state.samples = mutationsThisRun;
    state.stats = stats;
    // This process's chains, each as (index, size, state), to rank 0.
    ByteWriter local;
    for (int c : mine) {
        ByteWriter one;
        saveChain(c, one);
        local.put(uint32_t(c));
        local.putVector(one.bytes());
    }
    const std::vector<char> all = distributed::gatherBytesToRoot(local.bytes());
    const bool root = sumAllToRoot(film, state, resume_);
    ++result.checkpoints;
    last_ = std::chrono::steady_clock::now();
    if (!root) return;
    result.checkpointKept = "the bootstrap and " + std::to_string(chains_count_) + " chains after " +
                            std::to_string(state.samples) + " of " + std::to_string(total_) + " mutations";
    std::vector<std::span<const char>> byChain(static_cast<size_t>(chains_count_));
    ByteReader in(all, "the chains gathered for a checkpoint");
    while (!in.atEnd()) {
        const uint32_t c = in.get<uint32_t>();
        const std::span<const char> s = in.getSpan(size_t(in.get<uint64_t>()));
        if (c >= byChain.size()) throw std::logic_error("a checkpoint gathered chain " + std::to_string(c));
        byChain[c] = s;
    }
    ByteWriter out;
    out.put(kTag);
    out.put(uint32_t(chains_count_));
    out.putVector(bootstrap);
    for (size_t c = 0; c < byChain.size(); ++c) {
        if (byChain[c].empty()) throw std::logic_error("a checkpoint lacks chain " + std::to_string(c));
        out.put(uint64_t(byChain[c].size()));
        out.putBytes(byChain[c].data(), byChain[c].size());
    }
    state.chains = std::move(out.bytes());
    options_.checkpoint(state);
}

}  // namespace ps
