// The BxDF interface: scattering in the local shading frame (normal = +z).
// f() excludes the cosine factor; sample() returns f and the solid-angle pdf of wi.
// Specular lobes return f = (weight / |cos wi|) with pdf = the discrete probability
// of the lobe, and the Specular flag, so integrators treat every lobe alike.
#pragma once
#include <cstdint>
#include <optional>
#include "math/frame.h"
#include "math/spectrum.h"

namespace ps {

// Radiance: the path carries radiance from lights to the camera (path tracing).
// Importance: it carries importance from the camera (light tracing) and the BSDF must be
// the adjoint (thesis ch. 5: the 1/eta^2 radiance scaling applies only to Radiance).
enum class TransportMode { Radiance, Importance };
inline TransportMode adjoint(TransportMode m) {
    return m == TransportMode::Radiance ? TransportMode::Importance : TransportMode::Radiance;
}

enum BxDFFlags : uint8_t {
    kReflection = 1,
    kTransmission = 2,
    kDiffuse = 4,
    kGlossy = 8,
    kSpecular = 16,
};

struct BSDFSample {
    Spectrum f;
    Vec3 wi;
    float pdf = 0;
    uint8_t flags = 0;
    float eta = 1;  // relative index of refraction across the sampled transmission, 1 otherwise
    // Stochastic BxDFs (layered) return f/pdf with the right ratio but pdf only
    // proportional: MIS must ask pdf() for the true density.
    bool pdfIsProportional = false;
    bool isSpecular() const { return flags & kSpecular; }
    bool isTransmission() const { return flags & kTransmission; }
    bool isReflection() const { return flags & kReflection; }
};

// A BxDF seen from both sides of a connection: f(wo, wi), the density of sampling wi from wo,
// and the density of sampling wo from wi under the adjoint mode (thesis §10.2: the MIS
// weights of a bidirectional connection need both).
struct BxDFEval {
    Spectrum f;
    float pdfFwd = 0, pdfRev = 0;
};

class BxDF {
public:
    virtual ~BxDF() = default;
    // Whether sample() reads uc. Single-lobe BxDFs that ignore it say so at construction
    // (checked for every BxDF by the tests), and integrators then draw no sample for it.
    bool usesLobeSample() const { return usesLobeSample_; }
    virtual uint8_t flags() const = 0;
    virtual Spectrum f(Vec3 wo, Vec3 wi, TransportMode mode) const = 0;
    // uc picks among lobes, u picks the direction within a lobe.
    virtual std::optional<BSDFSample> sample(Vec3 wo, float uc, Vec2 u, TransportMode mode) const = 0;
    virtual float pdf(Vec3 wo, Vec3 wi, TransportMode mode) const = 0;
    virtual BxDFEval evaluate(Vec3 wo, Vec3 wi, TransportMode mode) const {
        return {f(wo, wi, mode), pdf(wo, wi, mode), pdf(wi, wo, adjoint(mode))};
    }
    bool isSpecular() const { return (flags() & (kDiffuse | kGlossy)) == 0 && (flags() & kSpecular); }

    // Layered BxDFs evaluate f() and pdf() as deterministic estimates and sample() by a
    // random walk of unknown density. Path-space Metropolis needs exact densities, so it
    // samples them itself (veach/path_space.cpp): their coating's mirror reflection, whose
    // reflectance at wo this gives (0 if the coating is rough), apart from the rest, which
    // has no delta unless the light can pass a smooth coating to a smooth base and back.
    virtual bool stochastic() const { return false; }
    virtual float coatingMirrorReflectance(Vec3 /*wo*/) const { return 0; }
    virtual bool specularThroughCoating() const { return false; }

protected:
    BxDF() = default;
    explicit BxDF(bool usesLobeSample) : usesLobeSample_(usesLobeSample) {}

private:
    bool usesLobeSample_ = true;
};

}  // namespace ps
