#include "materials/texture_mapping.h"

#include <cmath>

namespace ps {

TextureMapping2D TextureMapping2D::uv(float su, float sv, float du, float dv) {
    TextureMapping2D m;
    m.su_ = su;
    m.sv_ = sv;
    m.du_ = du;
    m.dv_ = dv;
    return m;
}

TextureMapping2D TextureMapping2D::spherical(const Transform& textureFromWorld) {
    TextureMapping2D m;
    m.kind_ = Kind::Spherical;
    m.textureFromWorld_ = textureFromWorld;
    return m;
}

TextureMapping2D TextureMapping2D::cylindrical(const Transform& textureFromWorld) {
    TextureMapping2D m;
    m.kind_ = Kind::Cylindrical;
    m.textureFromWorld_ = textureFromWorld;
    return m;
}

TextureMapping2D TextureMapping2D::planar(const Transform& textureFromWorld, Vec3 vs, Vec3 vt, float ds, float dt) {
    TextureMapping2D m;
    m.kind_ = Kind::Planar;
    m.textureFromWorld_ = textureFromWorld;
    m.vs_ = vs;
    m.vt_ = vt;
    m.du_ = ds;
    m.dv_ = dt;
    return m;
}

Vec2 TextureMapping2D::map(const TextureEvalContext& ctx) const {
    switch (kind_) {
        case Kind::UV: return {su_ * ctx.uv.x + du_, sv_ * ctx.uv.y + dv_};
        case Kind::Spherical: {
            Vec3 q = textureFromWorld_.point(ctx.p);
            float len = length(q);
            if (!(len > 0)) return {0, 0};  // the centre itself has no direction
            Vec3 w = q / len;
            float phi = std::atan2(w.y, w.x);
            if (phi < 0) phi += 2 * kPi;
            return {safeAcos(w.z) * kInvPi, phi * kInv2Pi};
        }
        case Kind::Cylindrical: {
            Vec3 q = textureFromWorld_.point(ctx.p);
            return {(kPi + std::atan2(q.y, q.x)) * kInv2Pi, q.z};
        }
        case Kind::Planar: {
            Vec3 q = textureFromWorld_.point(ctx.p);
            return {du_ + dot(q, vs_), dv_ + dot(q, vt_)};
        }
    }
    return {0, 0};
}

namespace {

Transform textureFromWorld(const Transform& worldFromTexture, const SourceLoc& loc, const std::string& what) {
    if (!worldFromTexture.isInvertible())
        throw InputError(loc, what + " needs the texture's transform (the CTM at Texture) to be invertible; it is singular");
    return worldFromTexture.inverse();
}

}  // namespace

TextureMapping2D textureMapping2D(const ParamSet& ps, const Transform& worldFromTexture, const SourceLoc& loc) {
    const std::string m = ps.getString("mapping", "uv");
    const std::string what = "texture mapping \"" + m + "\"";
    if (m == "spherical") return TextureMapping2D::spherical(textureFromWorld(worldFromTexture, loc, what));
    if (m == "cylindrical") return TextureMapping2D::cylindrical(textureFromWorld(worldFromTexture, loc, what));
    if (m == "planar")
        return TextureMapping2D::planar(textureFromWorld(worldFromTexture, loc, what), ps.getVector3("v1", Vec3(1, 0, 0)),
                                        ps.getVector3("v2", Vec3(0, 1, 0)), ps.getFloat("udelta", 0), ps.getFloat("vdelta", 0));
    if (m != "uv") {
        const Param* p = ps.find("mapping");
        warning(p ? p->loc : loc, "unknown texture mapping \"" + m + "\"; using \"uv\"");
    }
    return TextureMapping2D::uv(ps.getFloat("uscale", 1), ps.getFloat("vscale", 1), ps.getFloat("udelta", 0),
                                ps.getFloat("vdelta", 0));
}

TextureMapping3D textureMapping3D(const Transform& worldFromTexture, const SourceLoc& loc) {
    return TextureMapping3D(textureFromWorld(worldFromTexture, loc, "a 3-D texture"));
}

}  // namespace ps
