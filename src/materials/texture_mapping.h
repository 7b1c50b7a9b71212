// Where a shading point lies in a texture's own coordinates, with pbrt-v4's mappings
// (PBRT-CONVENTIONS §6). 2-D textures (image, checkerboard, dots, bilerp) read (s, t) from a
// TextureMapping2D: "uv" scales and offsets the surface's (u, v); "spherical", "cylindrical"
// and "planar" work on the point in texture space, i.e. the world point taken through the
// inverse of the CTM at the Texture directive. 3-D textures (fbm, wrinkled, windy, marble,
// the 3-D checkerboard) read that texture-space point itself.
//
// Point-sampled: pbrt-v4 also carries the coordinates' screen-space derivatives for
// filtering; with zero derivatives (its "disabletexturefiltering") it computes these values.
#pragma once
#include "materials/texture.h"
#include "math/transform.h"
#include "scene/params.h"

namespace ps {

class TextureMapping2D {
public:
    enum class Kind { UV, Spherical, Cylindrical, Planar };
    // The "uv" mapping with scales 1 and offsets 0: (s, t) = (u, v).
    TextureMapping2D() = default;
    // s = su u + du, t = sv v + dv.
    static TextureMapping2D uv(float su, float sv, float du, float dv);
    // With q the point in texture space (q = textureFromWorld(p)), direction w = q / |q|:
    // s = theta(w) / pi (0 at +z, 1 at -z), t = phi(w) / 2pi with phi = atan2(w.y, w.x) in [0, 2pi).
    static TextureMapping2D spherical(const Transform& textureFromWorld);
    // s = (pi + atan2(q.y, q.x)) / 2pi, t = q.z.
    static TextureMapping2D cylindrical(const Transform& textureFromWorld);
    // s = ds + dot(q, vs), t = dt + dot(q, vt) (vs, vt as given: not normalised).
    static TextureMapping2D planar(const Transform& textureFromWorld, Vec3 vs, Vec3 vt, float ds, float dt);

    Kind kind() const { return kind_; }
    Vec2 map(const TextureEvalContext& ctx) const;

private:
    Kind kind_ = Kind::UV;
    Transform textureFromWorld_;
    Vec3 vs_{1, 0, 0}, vt_{0, 1, 0};
    float su_ = 1, sv_ = 1, du_ = 0, dv_ = 0;  // uv: scales and offsets; planar: offsets du_, dv_
};

class TextureMapping3D {
public:
    explicit TextureMapping3D(const Transform& textureFromWorld = Transform()) : textureFromWorld_(textureFromWorld) {}
    Vec3 map(const TextureEvalContext& ctx) const { return textureFromWorld_.point(ctx.p); }

private:
    Transform textureFromWorld_;
};

// The mapping a Texture directive asks for: "string mapping" ("uv" by default) and its
// parameters (uscale, vscale, udelta, vdelta for uv; v1, v2, udelta, vdelta for planar),
// worldFromTexture the CTM at the directive. An unknown mapping warns and uses "uv"; a mapping
// that needs the transform's inverse throws InputError at loc when the CTM is singular.
TextureMapping2D textureMapping2D(const ParamSet& ps, const Transform& worldFromTexture, const SourceLoc& loc);
TextureMapping3D textureMapping3D(const Transform& worldFromTexture, const SourceLoc& loc);

}  // namespace ps
