// Checkpoints of a render: the film's exact sums after the last whole pass (and, when a
// uniform render stopped early, the samples of the pass it stopped in; for a Markov-chain
// render, the bootstrap's results and every chain's whole state), enough to continue it, on
// any number of processes, to the image one uninterrupted run gives. The file: a fixed
// binary header (magic, version, section sizes, a checksum of everything after it), JSON
// metadata (the settings that shape the image, where the render stands), then the sums as
// raw integers and the chains' state as bytes.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "film/film.h"
#include "transport/integrator.h"

namespace ps {

struct CheckpointState {
    int samplesPerPixel = 0;  // every pixel has taken sample indices [0, samplesPerPixel)
    int passSize = 1;         // the next pass's size (the growing pass schedule goes on), <= 64
    // A pass stopped part-way (the last checkpoint of a render stopped early): per pixel of
    // the crop region (row-major), bit k set when sample samplesPerPixel + k is in the sums
    // too, so that the resumed render takes only the others. Empty: no partial pass.
    std::vector<uint64_t> partial;
    long long samples = 0;    // camera samples in the sums
    PathStats stats;          // of those samples
    Film::Accumulators sums;  // over all processes (Film::accumulators)
    // A Markov-chain render (transport/mlt/chain_checkpoint.h): its bootstrap's results and
    // every chain's state, in chain order; empty for a uniform render. `samples` then counts
    // mutations.
    std::vector<char> chains;
    // The render that wrote it: its --spp, and where its sample sets after the first begin
    // (RenderOptions::sampleSets). A resume may raise --spp (never lower it).
    int spp = 0;
    std::vector<int> sampleSets;
};

// Writes atomically: a temporary file next to `path`, flushed to disk, then renamed over it,
// so a crash leaves the previous checkpoint or the new one, never a mix. `settings`: what
// must match to resume (checkpointSettings). Throws std::runtime_error naming the file.
void writeCheckpoint(const std::string& path, const nlohmann::json& settings, const CheckpointState& state);

// Reads and checks a checkpoint: throws InputError naming the file and what is wrong when it
// is not one, is truncated or corrupt (checksum), or was made with other settings (listing
// each that differs), so nothing is rendered or overwritten. Settings "spp" and
// "sample_sets" are not compared: the checkpoint's go to CheckpointState::spp and
// sampleSets, and a "spp" below the checkpoint's is refused.
CheckpointState readCheckpoint(const std::string& path, const nlohmann::json& settings);

// A 64-bit hash of a file's bytes, in hexadecimal (the scene's identity in the settings).
std::string fileHash(const std::string& path);

}  // namespace ps
