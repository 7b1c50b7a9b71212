#include "transport/checkpoint.h"

#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "mc/rng.h"
#include "util/atomic_file.h"
#include "util/error.h"

namespace ps {

namespace {

constexpr char kMagic[8] = {'P', 'S', 'C', 'K', 'P', 'T', '\n', '\0'};
// 2: the partial pass; 3: the chains' state; 4: the film's sums in units of 2^-40 (2^-64
// before), which an earlier file's sums cannot be read as, so it is refused; 6: the two-stage
// pilot map's tile size (a time budget may shrink the pilot, and its tiles with it).
constexpr uint32_t kVersion = 6;
constexpr uint32_t kByteOrder = 0x01020304;  // read back otherwise on a machine of the other order

struct Header {
    char magic[8];
    uint32_t version, byteOrder;
    uint64_t metadataBytes, fixedCount, countCount, partialCount;
    uint64_t checksum;  // of every byte after the header
    uint64_t chainBytes;
};
static_assert(sizeof(Header) == 64);
// The fields every version has where it has them: enough to read the version (56 bytes).
constexpr size_t kCommonHeaderBytes = 56;

// A 64-bit hash, eight bytes at a time: not cryptographic, it catches a damaged file.
uint64_t hashBytes(const char* data, size_t n, uint64_t h) {
    size_t i = 0;
    for (; i + 8 <= n; i += 8) {
        uint64_t w;
        std::memcpy(&w, data + i, 8);
        h = mix64(h ^ w) + i;
    }
    uint64_t tail = 0;
    if (n > i) std::memcpy(&tail, data + i, n - i);  // data may be null when n is 0
    return mix64(h ^ tail ^ (uint64_t(n) << 3));
}

nlohmann::json statsJson(const PathStats& s) {
    return {s.cameraPaths, s.lightPaths, s.rays, s.shadowRays, s.guarded, s.shadowRaysSkipped};
}

// For a setting that maps file names to hashes: each file that differs.
std::string fileDifferences(const nlohmann::json& want, const nlohmann::json& have) {
    std::string d;
    auto add = [&](const std::string& s) { d += (d.empty() ? "" : "; ") + s; };
    for (const auto& [file, hash] : want.items()) {
        const auto it = have.find(file);
        if (it == have.end()) add("the scene reads \"" + file + "\", which the checkpoint's render did not read");
        else if (*it != hash)
            add("\"" + file + "\" has changed since the checkpoint (hash " + hash.dump() + " here, " + it->dump() + " then)");
    }
    for (const auto& [file, hash] : have.items())
        if (!want.contains(file)) add("the checkpoint's render read \"" + file + "\", which the scene no longer reads");
    return d;
}

// The settings a resume may change: the sample count (raised) and, with it, the sample sets.
bool mayChange(const std::string& key) { return key == "spp" || key == "sample_sets"; }

// "seed 2 here, 1 in the checkpoint; integrator ..." for every setting that differs.
std::string differences(const nlohmann::json& want, const nlohmann::json& have) {
    std::string d;
    for (const auto& [key, value] : want.items()) {
        if (mayChange(key)) continue;
        const auto it = have.find(key);
        if (value.is_object() && it != have.end() && it->is_object()) {
            const std::string f = fileDifferences(value, *it);
            if (!f.empty()) d += (d.empty() ? "" : "; ") + f;
            continue;
        }
        const std::string old = it == have.end() ? "absent" : it->dump();
        if (it == have.end() || *it != value)
            d += (d.empty() ? "" : "; ") + key + " " + value.dump() + " here, " + old + " in the checkpoint";
    }
    return d;
}

[[noreturn]] void refuse(const std::string& path, const std::string& what) {
    throw InputError("--resume \"" + path + "\": " + what + "; nothing was rendered or overwritten");
}

}  // namespace

std::string fileHash(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", (unsigned long long)hashBytes(bytes.data(), bytes.size(), 0));
    return hex;
}

void writeCheckpoint(const std::string& path, const nlohmann::json& settings, const CheckpointState& state) {
    const std::string metadata = nlohmann::json{{"settings", settings},
                                                {"samples_per_pixel", state.samplesPerPixel},
                                                {"pass_size", state.passSize},
                                                {"samples", state.samples},
                                                {"stats", statsJson(state.stats)}}
                                     .dump();
    const auto& fixed = state.sums.fixed;
    const auto& counts = state.sums.counts;
    const auto& partial = state.partial;
    Header h{};
    std::memcpy(h.magic, kMagic, 8);
    h.version = kVersion;
    h.byteOrder = kByteOrder;
    h.metadataBytes = metadata.size();
    h.fixedCount = fixed.size();
    h.countCount = counts.size();
    h.partialCount = partial.size();
    h.chainBytes = state.chains.size();
    uint64_t c = hashBytes(metadata.data(), metadata.size(), 1);
    c = hashBytes(reinterpret_cast<const char*>(fixed.data()), fixed.size() * sizeof(Fixed), c);
    c = hashBytes(reinterpret_cast<const char*>(counts.data()), counts.size() * sizeof(int64_t), c);
    c = hashBytes(reinterpret_cast<const char*>(partial.data()), partial.size() * sizeof(uint64_t), c);
    h.checksum = hashBytes(state.chains.data(), state.chains.size(), c);

    auto bytes = [](const void* p, size_t n) { return std::span<const char>(static_cast<const char*>(p), n); };
    writeFileAtomically(path,
                        {bytes(&h, sizeof h), bytes(metadata.data(), metadata.size()),
                         bytes(fixed.data(), fixed.size() * sizeof(Fixed)), bytes(counts.data(), counts.size() * sizeof(int64_t)),
                         bytes(partial.data(), partial.size() * sizeof(uint64_t)),
                         bytes(state.chains.data(), state.chains.size())},
                        "checkpoint");
}

CheckpointState readCheckpoint(const std::string& path, const nlohmann::json& settings) {
    std::ifstream in(path, std::ios::binary);
    if (!in) refuse(path, "cannot open the file");
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    Header h{};
    if (bytes.size() < kCommonHeaderBytes || std::memcmp(bytes.data(), kMagic, 8) != 0)
        refuse(path, "not a pathspace checkpoint");
    std::memcpy(&h, bytes.data(), kCommonHeaderBytes);
    if (h.byteOrder != kByteOrder) refuse(path, "written on a machine of the other byte order");
    if (h.version != kVersion)
        refuse(path, "format version " + std::to_string(h.version) + ", this pathspace reads version " +
                         std::to_string(kVersion) + (h.version < kVersion ? " only (an earlier pathspace wrote another "
                                                                            "layout): render again without --resume"
                                                                          : " only"));
    const size_t headerBytes = sizeof h;
    if (bytes.size() < headerBytes) refuse(path, "truncated or damaged: shorter than its header");
    std::memcpy(&h, bytes.data(), headerBytes);
    // Sizes first (a truncated file), in a way no huge count in a damaged header overflows.
    const long double expected = (long double)headerBytes + h.metadataBytes + (long double)h.fixedCount * sizeof(Fixed) +
                                 (long double)h.countCount * sizeof(int64_t) + (long double)h.partialCount * sizeof(uint64_t) +
                                 (long double)h.chainBytes;
    if (expected != (long double)bytes.size())
        refuse(path, "truncated or damaged: its header announces " + std::to_string((unsigned long long)expected) +
                         " bytes, the file has " + std::to_string(bytes.size()));
    const char* at = bytes.data() + headerBytes;
    const char* fixedAt = at + h.metadataBytes;
    const char* countsAt = fixedAt + h.fixedCount * sizeof(Fixed);
    const char* partialAt = countsAt + h.countCount * sizeof(int64_t);
    const char* chainsAt = partialAt + h.partialCount * sizeof(uint64_t);
    uint64_t c = hashBytes(at, h.metadataBytes, 1);
    c = hashBytes(fixedAt, h.fixedCount * sizeof(Fixed), c);
    c = hashBytes(countsAt, h.countCount * sizeof(int64_t), c);
    c = hashBytes(partialAt, h.partialCount * sizeof(uint64_t), c);
    c = hashBytes(chainsAt, h.chainBytes, c);
    if (c != h.checksum)
        refuse(path, "corrupt (its checksum does not match its contents)");
    CheckpointState s;
    try {
        const nlohmann::json m = nlohmann::json::parse(bytes.substr(headerBytes, h.metadataBytes));
        const std::string diff = differences(settings, m.at("settings"));
        if (!diff.empty()) refuse(path, "made for another render (" + diff + ")");
        s.spp = m.at("settings").at("spp").get<int>();
        s.sampleSets = m.at("settings").value("sample_sets", std::vector<int>());
        if (settings.contains("spp") && settings.at("spp").get<int>() < s.spp)
            refuse(path, "made for --spp " + std::to_string(s.spp) + ": a resume may raise --spp, not lower it (--spp " +
                             settings.at("spp").dump() + " here)");
        s.samplesPerPixel = m.at("samples_per_pixel").get<int>();
        s.passSize = m.at("pass_size").get<int>();
        if (s.passSize < 1 || s.passSize > 64) refuse(path, "damaged: pass size " + std::to_string(s.passSize));
        s.samples = m.at("samples").get<long long>();
        const auto& st = m.at("stats");
        s.stats = {st.at(0).get<uint64_t>(), st.at(1).get<uint64_t>(), st.at(2).get<uint64_t>(), st.at(3).get<uint64_t>(),
                   st.at(4).get<uint64_t>()};
        // Checkpoints written before shadow-ray roulette have five counts.
        if (st.size() > 5) s.stats.shadowRaysSkipped = st.at(5).get<uint64_t>();
    } catch (const nlohmann::json::exception& e) {
        refuse(path, std::string("unreadable metadata (") + e.what() + ")");
    }
    s.sums.fixed.resize(h.fixedCount);
    s.sums.counts.resize(h.countCount);
    s.partial.resize(h.partialCount);
    // An empty vector's data() may be null, which memcpy must not get even for 0 bytes.
    auto copy = [](void* to, const char* from, size_t bytes) {
        if (bytes > 0) std::memcpy(to, from, bytes);
    };
    copy(s.sums.fixed.data(), fixedAt, h.fixedCount * sizeof(Fixed));
    copy(s.sums.counts.data(), countsAt, h.countCount * sizeof(int64_t));
    copy(s.partial.data(), partialAt, h.partialCount * sizeof(uint64_t));
    s.chains.assign(chainsAt, chainsAt + h.chainBytes);
    return s;
}

}  // namespace ps
