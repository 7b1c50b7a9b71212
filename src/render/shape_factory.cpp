#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "geometry/alpha_mask.h"
#include "geometry/curve.h"
#include "geometry/loop_subdivision.h"
#include "geometry/quadric.h"
#include "geometry/triangle_mesh.h"
#include "materials/create.h"
#include "materials/textures.h"
#include "render/scene_builder.h"
#include "scene/ply_cache.h"
#include "util/memory_limit.h"

namespace ps {

namespace {

// Checks indices against the vertex count and drops a trailing partial triangle.
void validateIndices(std::vector<int>& indices, size_t nVertices, const SourceLoc& loc, const char* what) {
    if (indices.size() % 3 != 0) {
        warning(loc, std::string(what) + ": number of indices is not a multiple of 3; extra ones ignored");
        indices.resize(indices.size() / 3 * 3);
    }
    for (int i : indices)
        if (i < 0 || size_t(i) >= nVertices)
            throw InputError(loc, std::string(what) + ": vertex index " + std::to_string(i) + " out of range [0, " +
                                      std::to_string(nVertices) + ")");
}

// pbrt-v4 quads/bilinear patches (p00 p10 p01 p11) approximated by two triangles
// (exact for planar parallelograms).
void appendBilinearAsTriangles(std::vector<int>& tris, int p00, int p10, int p01, int p11) {
    tris.insert(tris.end(), {p00, p10, p11, p00, p11, p01});
}

std::unique_ptr<Shape> createTriangleMesh(const ShapeEntity& e, const Transform& toScene) {
    const ParamSet& ps = e.params;
    TriangleMeshData d;
    d.P = ps.getPoint3s("P");
    d.indices = ps.getInts("indices");
    d.N = ps.getNormals("N");
    d.uv = ps.getPoint2s("uv");
    ps.getVector3s("S");  // tangents: accepted, frames follow dp/du
    if (d.P.empty()) throw InputError(e.loc, "trianglemesh: \"point3 P\" is required");
    if (d.indices.empty()) {
        if (d.P.size() != 3) throw InputError(e.loc, "trianglemesh: \"integer indices\" is required unless there are exactly 3 points");
        d.indices = {0, 1, 2};
    }
    validateIndices(d.indices, d.P.size(), e.loc, "trianglemesh");
    if (!d.N.empty() && d.N.size() != d.P.size()) {
        warning(e.loc, "trianglemesh: \"normal N\" count does not match \"point3 P\"; normals ignored");
        d.N.clear();
    }
    if (!d.uv.empty() && d.uv.size() != d.P.size()) {
        warning(e.loc, "trianglemesh: \"point2 uv\" count does not match \"point3 P\"; uv ignored");
        d.uv.clear();
    }
    return std::make_unique<TriangleMesh>(std::move(d), toScene, e.reverseOrientation);
}

std::unique_ptr<Shape> createBilinearMesh(const ShapeEntity& e, const Transform& toScene) {
    const ParamSet& ps = e.params;
    TriangleMeshData d;
    d.P = ps.getPoint3s("P");
    std::vector<int> quads = ps.getInts("indices");
    d.N = ps.getNormals("N");
    d.uv = ps.getPoint2s("uv");
    if (d.P.empty()) throw InputError(e.loc, "bilinearmesh: \"point3 P\" is required");
    if (quads.empty()) {
        if (d.P.size() != 4) throw InputError(e.loc, "bilinearmesh: \"integer indices\" is required unless there are exactly 4 points");
        quads = {0, 1, 2, 3};
    }
    if (quads.size() % 4 != 0) {
        warning(e.loc, "bilinearmesh: number of indices is not a multiple of 4; extra ones ignored");
        quads.resize(quads.size() / 4 * 4);
    }
    for (int i : quads)
        if (i < 0 || size_t(i) >= d.P.size())
            throw InputError(e.loc, "bilinearmesh: vertex index " + std::to_string(i) + " out of range");
    if (d.N.size() != d.P.size()) d.N.clear();
    if (d.uv.empty()) {
        // Patch parameterisation: (0,0) (1,0) (0,1) (1,1) per patch needs per-patch vertices.
        std::vector<Vec3> P, N;
        for (size_t q = 0; q < quads.size(); q += 4) {
            int base = int(P.size());
            for (int k = 0; k < 4; ++k) {
                P.push_back(d.P[quads[q + k]]);
                if (!d.N.empty()) N.push_back(d.N[quads[q + k]]);
                d.uv.push_back(Vec2(float(k & 1), float(k >> 1)));
            }
            appendBilinearAsTriangles(d.indices, base, base + 1, base + 2, base + 3);
        }
        d.P = std::move(P);
        d.N = std::move(N);
    } else {
        if (d.uv.size() != d.P.size()) d.uv.clear();
        for (size_t q = 0; q < quads.size(); q += 4)
            appendBilinearAsTriangles(d.indices, quads[q], quads[q + 1], quads[q + 2], quads[q + 3]);
    }
    return std::make_unique<TriangleMesh>(std::move(d), toScene, e.reverseOrientation);
}

std::unique_ptr<Shape> createPlyMesh(const ShapeEntity& e, const Transform& toScene, const std::string& base) {
    std::string file = e.params.getString("filename", "");
    if (file.empty()) throw InputError(e.loc, "plymesh: \"string filename\" is required");
    if (e.params.has("displacement"))
        warning(e.loc, "plymesh: \"displacement\" is not supported yet; the mesh is rendered undisplaced");
    e.params.getTexture("displacement");
    e.params.getFloat("edgelength", 1);
    PlyMesh ply = readNamedBy(e.loc, [&] { return readPlyCached(resolvePath(base, file)); });
    TriangleMeshData d;
    d.P = std::move(ply.P);
    d.N = std::move(ply.N);
    d.uv = std::move(ply.uv);
    d.indices = std::move(ply.triIndices);
    for (size_t q = 0; q + 3 < ply.quadIndices.size(); q += 4) {
        const int* v = &ply.quadIndices[q];
        // A PLY quad v0 v1 v2 v3 is the patch p00=v0, p10=v1, p01=v3, p11=v2.
        appendBilinearAsTriangles(d.indices, v[0], v[1], v[3], v[2]);
    }
    if (d.indices.empty()) throw InputError(e.loc, "plymesh: \"" + file + "\" has no triangles or quads");
    return std::make_unique<TriangleMesh>(std::move(d), toScene, e.reverseOrientation);
}

// pbrt-v4's "loopsubdiv": subdivided to `levels` (default 3) and pushed to the limit
// surface, with limit normals; then an ordinary triangle mesh.
std::unique_ptr<Shape> createLoopSubdiv(const ShapeEntity& e, const Transform& toScene) {
    const ParamSet& ps = e.params;
    const int levels = std::max(0, ps.getInt("levels", 3));  // pbrt-v4: fewer than 0 levels is 0
    std::vector<int> indices = ps.getInts("indices");
    std::vector<Vec3> P = ps.getPoint3s("P");
    ps.getString("scheme", "loop");  // read and ignored by pbrt-v4 too: the scheme is always Loop's
    if (indices.empty()) throw InputError(e.loc, "loopsubdiv: \"integer indices\" is required");
    if (P.empty()) throw InputError(e.loc, "loopsubdiv: \"point3 P\" is required");
    validateIndices(indices, P.size(), e.loc, "loopsubdiv");
    // Each level quadruples the triangles; ~200 bytes per final triangle while subdividing,
    // in the mesh and in Embree's BVH.
    const double triangles = double(indices.size() / 3) * std::pow(4.0, levels);
    char what[96];
    std::snprintf(what, sizeof what, "loopsubdiv: %d levels (%.3g triangles)", levels, triangles);
    requireMemory(e.loc, what, triangles * 200);
    try {
        return std::make_unique<TriangleMesh>(loopSubdivide(levels, indices, P), toScene, e.reverseOrientation);
    } catch (const std::invalid_argument& err) {
        throw InputError(e.loc, std::string("loopsubdiv: ") + err.what());
    }
}

// pbrt-v4's "curve": what pbrt-v4 reports as an error and then skips is a warning here and
// the curve is ignored, as there; an area light on a curve is an error (pbrt-v4 cannot
// sample points on curves and stops when it tries).
std::unique_ptr<Shape> createCurve(const ShapeEntity& e, const Transform& toScene) {
    const ParamSet& ps = e.params;
    CurveInput in;
    in.P = ps.getPoint3s("P");
    in.N = ps.getNormals("N");
    in.degree = ps.getInt("degree", 3);
    const float width = ps.getFloat("width", 1);
    in.width0 = ps.getFloat("width0", width);
    in.width1 = ps.getFloat("width1", width);
    const std::string basis = ps.getString("basis", "bezier");
    const std::string type = ps.getString("type", "flat");
    ps.getInt("splitdepth", 3);  // pbrt-v4 splits segments for its own intersector; Embree needs no split
    if (e.areaLight >= 0)
        throw InputError(e.loc, "curve: area lights on curves are not supported (pbrt-v4 cannot sample them either)");
    if (type == "flat") {
        in.type = CurveType::Flat;
    } else if (type == "ribbon") {
        in.type = CurveType::Ribbon;
    } else if (type == "cylinder") {
        in.type = CurveType::Cylinder;
    } else {
        warning(e.loc, "curve: unknown \"type\" " + quoteForMessage(type) + "; using \"cylinder\"");
        in.type = CurveType::Cylinder;
    }
    if (basis != "bezier" && basis != "bspline") {
        warning(e.loc, "curve: invalid \"basis\" " + quoteForMessage(basis) +
                           ": only \"bezier\" and \"bspline\" are supported; the curve is ignored");
        return nullptr;
    }
    in.bspline = basis == "bspline";
    if (!in.N.empty() && in.type != CurveType::Ribbon) {
        warning(e.loc, "curve: normals \"N\" are only used by \"ribbon\" curves; ignored");
        in.N.clear();
    }
    if (in.width0 < 0 || in.width1 < 0) {
        warning(e.loc, "curve: negative width; the curve is ignored");
        return nullptr;
    }
    CurveSegments segments;
    std::string err = makeSegments(in, segments);
    if (!err.empty()) {
        warning(e.loc, "curve: " + err + "; the curve is ignored");
        return nullptr;
    }
    return std::make_unique<Curve>(segments, in.type, toScene, e.reverseOrientation);
}

// "float alpha" or "texture alpha"; null (opaque, no filter) for a constant alpha >= 1, the default.
// A "constant" texture is a constant alpha, as pbrt-v4 takes it: constant 0 is an invisible
// shape and, on an emitter, pbrt-v4's invisible light.
std::shared_ptr<const AlphaMask> alphaMask(const ParamSet& ps, const TextureRegistry& textures) {
    if (!ps.has("alpha")) return nullptr;
    std::shared_ptr<FloatTexture> tex = floatTextureParam(ps, "alpha", 1, textures);
    if (auto c = dynamic_cast<const ConstantTexture<float>*>(tex.get())) {
        float a = c->value();
        return a >= 1 ? nullptr : std::make_shared<AlphaMask>(nullptr, a);
    }
    return std::make_shared<AlphaMask>(std::move(tex));
}

}  // namespace

std::unique_ptr<Shape> createShape(const ShapeEntity& e, const Transform& toScene, const std::string& base,
                                   const TextureRegistry& textures) {
    const ParamSet& ps = e.params;
    std::unique_ptr<Shape> shape;
    std::shared_ptr<const AlphaMask> alpha = alphaMask(ps, textures);
    if (e.type == "trianglemesh") {
        shape = createTriangleMesh(e, toScene);
    } else if (e.type == "plymesh") {
        shape = createPlyMesh(e, toScene, base);
    } else if (e.type == "bilinearmesh") {
        shape = createBilinearMesh(e, toScene);
    } else if (e.type == "loopsubdiv") {
        shape = createLoopSubdiv(e, toScene);
    } else if (e.type == "sphere") {
        float r = ps.getFloat("radius", 1);
        if (!(r > 0)) throw InputError(e.loc, "sphere: \"radius\" must be positive");
        shape = std::make_unique<Sphere>(toScene, e.reverseOrientation, r, ps.getFloat("zmin", -r), ps.getFloat("zmax", r),
                                         ps.getFloat("phimax", 360));
    } else if (e.type == "disk") {
        float r = ps.getFloat("radius", 1);
        if (!(r > 0)) throw InputError(e.loc, "disk: \"radius\" must be positive");
        shape = std::make_unique<Disk>(toScene, e.reverseOrientation, ps.getFloat("height", 0), r,
                                       ps.getFloat("innerradius", 0), ps.getFloat("phimax", 360));
    } else if (e.type == "cylinder") {
        float r = ps.getFloat("radius", 1);
        if (!(r > 0)) throw InputError(e.loc, "cylinder: \"radius\" must be positive");
        shape = std::make_unique<Cylinder>(toScene, e.reverseOrientation, r, ps.getFloat("zmin", -1), ps.getFloat("zmax", 1),
                                           ps.getFloat("phimax", 360));
    } else if (e.type == "curve") {
        shape = createCurve(e, toScene);
        if (!shape) return nullptr;
    } else {
        warning(e.loc, "Shape \"" + e.type + "\" is not supported; it is ignored");
        return nullptr;
    }
    ps.reportUnused("Shape \"" + e.type + "\"");
    shape->alpha = std::move(alpha);
    return shape;
}

}  // namespace ps
