#include "materials/shading_detail.h"

#include "math/frame.h"

namespace ps {

std::shared_ptr<const ShadingDetail> ShadingDetail::normalMap(std::shared_ptr<const Image> image) {
    auto d = std::make_shared<ShadingDetail>();
    d->lookup_ = std::make_unique<ImageLookup>(std::move(image), TextureMapping2D{}, WrapMode::Repeat, 1.0f, false,
                                               ImageChannels::RGB);
    return d;
}

std::shared_ptr<const ShadingDetail> ShadingDetail::bumpMap(std::shared_ptr<FloatTexture> displacement) {
    auto d = std::make_shared<ShadingDetail>();
    d->displacement_ = std::move(displacement);
    return d;
}

// The map's normal in the frame x = dp/du (unit), z = shading normal; dp/du made orthogonal
// to it, dp/dv = n x dp/du, both keeping their lengths.
void ShadingDetail::normalMapped(const SurfaceInteraction& si, Vec3& dpdu, Vec3& dpdv) const {
    Spectrum c = lookup_->bilinear(si.uv);
    Vec3 local = normalize(Vec3(2 * c.r - 1, 2 * c.g - 1, 2 * c.b - 1));
    Vec3 x = normalize(si.dpdu);
    Vec3 n = Frame(x, cross(si.ns, x), si.ns).toWorld(local);
    float ulen = length(si.dpdu), vlen = length(si.dpdv);
    dpdu = normalize(si.dpdu - n * dot(n, si.dpdu)) * ulen;
    dpdv = normalize(cross(n, dpdu)) * vlen;
}

// The displaced surface p + d(u, v) n has partials dp/du + (dd/du) n + d dn/du (and the same
// in v); dd/du by a forward difference whose shifted point moves along dp/du as well.
void ShadingDetail::bumped(const SurfaceInteraction& si, Vec3& dpdu, Vec3& dpdv) const {
    const float du = kBumpDelta, dv = kBumpDelta;
    TextureEvalContext here{si.p, si.ng, si.uv};
    TextureEvalContext alongU{si.p + si.dpdu * du, si.ng, si.uv + Vec2(du, 0)};
    TextureEvalContext alongV{si.p + si.dpdv * dv, si.ng, si.uv + Vec2(0, dv)};
    float d = displacement_->evaluate(here);
    float dU = displacement_->evaluate(alongU), dV = displacement_->evaluate(alongV);
    dpdu = si.dpdu + si.ns * ((dU - d) / du) + si.dndu * d;
    dpdv = si.dpdv + si.ns * ((dV - d) / dv) + si.dndv * d;
}

void ShadingDetail::apply(SurfaceInteraction& si) const {
    Vec3 dpdu, dpdv;
    if (lookup_) normalMapped(si, dpdu, dpdv);
    else bumped(si, dpdu, dpdv);
    Vec3 n = cross(dpdu, dpdv);
    float l = length(n);
    if (!(l > 0) || !std::isfinite(l) || !isFinite(dpdu) || !(lengthSquared(dpdu) > 0)) return;
    n = n / l;
    si.ns = dot(n, si.ng) < 0 ? -n : n;
    si.dpdu = dpdu;
    si.dpdv = dpdv;
    si.tangentIsFrameAxis = false;
}

}  // namespace ps
