#include "variants.h"

#include <cmath>
#include <filesystem>

#include "image/image.h"

namespace ps::test {

namespace {

// The base light's quad under the ceiling, facing down, with `emission` (AreaLightSource's
// parameters).
// The film, filter and Integrator lines every variant shares (an N x N film).
// `integrator`: more of the Integrator's parameters.
std::string filmAndDepth(int n, int maxDepth, const std::string& integrator = "") {
    const std::string res = std::to_string(n);
    return "Film \"rgb\" \"integer xresolution\" [ " + res + " ] \"integer yresolution\" [ " + res +
           " ]\nPixelFilter \"box\"\nIntegrator \"path\" \"integer maxdepth\" [ " + std::to_string(maxDepth) +
           " ] " + integrator + "\nWorldBegin\n";
}

std::string quadLight(const std::string& emission) {
    return R"(AttributeBegin
  AreaLightSource "diffuse" )" + emission + R"(
  Shape "bilinearmesh" "point3 P" [ -0.2 0.99 -0.2   0.2 0.99 -0.2   -0.2 0.99 0.2   0.2 0.99 0.2 ]
AttributeEnd)";
}

// The base scene: a 1 x 1 x 1 box open towards the camera, lit by a quad under its ceiling,
// with coloured side walls and a sphere on the floor. Each field is one feature's place.
struct Box {
    std::string camera = R"(LookAt 0 0.5 2.2  0 0.5 0  0 1 0
Camera "perspective" "float fov" [ 30 ])";
    int maxDepth = 5;
    std::string integrator;   // more Integrator parameters
    std::string environment;  // infinite and distant lights
    std::string light = quadLight(R"("rgb L" [ 5 5 5 ])");
    std::string floorMaterial = R"(Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ])";
    std::string objectMaterial = R"(Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.8 ])";
    std::string object = R"(AttributeBegin
  Translate 0 0.25 0
  Shape "sphere" "float radius" [ 0.25 ]
AttributeEnd)";
    std::string extra;

    std::string text() const {
        return camera + "\n" + filmAndDepth(24, maxDepth, integrator) + environment + "\n" + light +
               "\n" + floorMaterial + R"(
Shape "bilinearmesh" "point3 P" [ -0.5 0 0.5   0.5 0 0.5   -0.5 0 -0.5   0.5 0 -0.5 ]
Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]
Shape "bilinearmesh" "point3 P" [ -0.5 1 -0.5   0.5 1 -0.5   -0.5 1 0.5   0.5 1 0.5 ]
Shape "bilinearmesh" "point3 P" [ -0.5 0 -0.5   0.5 0 -0.5   -0.5 1 -0.5   0.5 1 -0.5 ]
Material "diffuse" "rgb reflectance" [ 0.7 0.2 0.2 ]
Shape "bilinearmesh" "point3 P" [ -0.5 0 0.5   -0.5 0 -0.5   -0.5 1 0.5   -0.5 1 -0.5 ]
Material "diffuse" "rgb reflectance" [ 0.2 0.7 0.2 ]
Shape "bilinearmesh" "point3 P" [ 0.5 0 -0.5   0.5 0 0.5   0.5 1 -0.5   0.5 1 0.5 ]
)" + objectMaterial +
               "\n" + object + "\n" + extra + "\n";
    }
};

// A sphere lit from inside by its own emission (reflectance `albedo`): every pixel sees
// Le sum_{k <= maxdepth} albedo^k, whatever the camera (inside the sphere).
std::string furnace(const std::string& camera, double albedo, int maxDepth) {
    return camera + "\n" + filmAndDepth(16, maxDepth) + R"(AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]
Material "diffuse" "rgb reflectance" [ )" +
           std::to_string(albedo) + " " + std::to_string(albedo) + " " + std::to_string(albedo) + R"( ]
ReverseOrientation
Shape "sphere" "float radius" [ 3 ]
)";
}
double furnaceValue(double albedo, int maxDepth) {
    double v = 0;
    for (int k = 0; k <= maxDepth; ++k) v += std::pow(albedo, k);
    return v;
}

// A sphere-shaped emitter of radius 0.1 under the ceiling, with `material`.
std::string emissiveSphere(const std::string& material) {
    return "AttributeBegin\n  " + material + R"(
  AreaLightSource "diffuse" "rgb L" [ 10 10 10 ]
  Translate 0 0.8 0
  Shape "sphere" "float radius" [ 0.1 ]
AttributeEnd)";
}

// An n x n grid of triangles facing down at height y, spanning [-h, h] in x and z.
std::string triangleGrid(int n, double h, double y) {
    std::string P, idx;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
            P += std::to_string(-h + 2 * h * i / n) + " " + std::to_string(y) + " " + std::to_string(-h + 2 * h * j / n) + "  ";
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
            // (b - a) x (c - a) points down: the emitting side faces the room.
            idx += std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(c) + "  " + std::to_string(b) +
                   " " + std::to_string(d) + " " + std::to_string(c) + "  ";
        }
    return "Shape \"trianglemesh\" \"point3 P\" [ " + P + "] \"integer indices\" [ " + idx + "]";
}

// Small images the scenes read, written once per process.
void writeData(const std::string& dir) {
    std::filesystem::create_directories(dir);
    Image env(16, 16), slide(8, 8), checker(8, 8), gonio(8, 8);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
            env.set(x, y, Spectrum(0.2f + 0.8f * x / 15, 0.3f + 0.5f * y / 15, 0.6f));
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            const bool on = (x / 2 + y / 2) % 2;
            slide.set(x, y, on ? Spectrum(1, 0.8f, 0.4f) : Spectrum(0.2f, 0.3f, 0.9f));
            checker.set(x, y, on ? Spectrum(0.8f, 0.6f, 0.2f) : Spectrum(0.1f, 0.4f, 0.6f));
            gonio.set(x, y, Spectrum(0.3f + 0.7f * float(x + y) / 14));
        }
    writeImage(dir + "/env.pfm", env);
    writeImage(dir + "/slide.pfm", slide);
    writeImage(dir + "/checker.pfm", checker);
    writeImage(dir + "/gonio.pfm", gonio);
}

}  // namespace

std::string testName(const std::string& variant) {
    std::string s;
    for (char c : variant) s += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    return s;
}

std::vector<Variant> agreementVariants(const std::string& dir) {
    writeData(dir);
    const std::string data = std::string(PATHSPACE_SOURCE_DIR) + "/tests/data";
    std::vector<Variant> v;
    const Box base;
    auto box = [&](const std::string& name, auto&& change, std::set<std::string> cannot = {}) {
        Box b;
        change(b);
        Variant var;
        var.name = name;
        var.scene = b.text();
        var.cannot = std::move(cannot);
        v.push_back(var);
        return &v.back();
    };
    auto none = [](Box&) {};
    const std::set<std::string> noLight{"light"};
    // Cameras without importance: light tracing and Veach's lens mutations need it.
    const std::set<std::string> lensless{"light", "mlt"};

    // ---- lights ----
    box("base", none);
    // The light turned to the ceiling: the camera never sees its emitting side, and the room
    // is lit by the ceiling alone.
    box("light/area-not-seen", [](Box& b) {
        b.light = R"(AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 8 8 8 ]
  Shape "bilinearmesh" "point3 P" [ -0.2 0.9 0.2   0.2 0.9 0.2   -0.2 0.9 -0.2   0.2 0.9 -0.2 ]
AttributeEnd)";
    })->integratorScale = {{"path", 8}};  // the ceiling's hot spot over the light
    box("light/area-two-sided", [](Box& b) {
        b.light = R"(AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 4 4 4 ] "bool twosided" true
  Shape "bilinearmesh" "point3 P" [ -0.2 0.9 -0.2   0.2 0.9 -0.2   -0.2 0.9 0.2   0.2 0.9 0.2 ]
AttributeEnd)";
    });
    // The base light's quad wound the other way, its emitting side turned back to the room.
    box("light/area-reversed", [](Box& b) {
        b.light = R"(AttributeBegin
  ReverseOrientation
  AreaLightSource "diffuse" "rgb L" [ 5 5 5 ]
  Shape "bilinearmesh" "point3 P" [ -0.2 0.99 0.2   0.2 0.99 0.2   -0.2 0.99 -0.2   0.2 0.99 -0.2 ]
AttributeEnd)";
    })->sameAs = base.text();
    // The same emission through "scale": the image must not change.
    box("light/scale", [](Box& b) {
        b.light = quadLight(R"("rgb L" [ 2 2 2 ] "float scale" [ 2.5 ])");
    })->sameAs = base.text();
    box("light/power", [](Box& b) {
        b.light = quadLight(R"("rgb L" [ 1 0.8 0.6 ] "float power" [ 2 ])");
    });
    box("light/blackbody", [](Box& b) {
        b.light = quadLight(R"("blackbody L" [ 3000 ] "float scale" [ 5 ])");
    });
    box("light/named-spectrum", [](Box& b) {
        b.light = quadLight(R"("spectrum L" "stdillum-F4" "float scale" [ 5 ])");
    });
    // Small emitters: a Metropolis bootstrap finds them less often (b's error is larger).
    box("light/sphere-black-material", [](Box& b) {
        b.light = emissiveSphere(R"(Material "diffuse" "rgb reflectance" [ 0 0 0 ])");
    })->sppScale = 2;
    box("light/sphere-coloured-material", [](Box& b) {
        b.light = emissiveSphere(R"(Material "diffuse" "rgb reflectance" [ 0.6 0.4 0.2 ])");
    })->sppScale = 2;
    box("light/cylinder", [](Box& b) {
        b.light = R"(AttributeBegin
  Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
  AreaLightSource "diffuse" "rgb L" [ 8 8 8 ]
  Translate 0 0.8 0
  Rotate 90 0 1 0
  Shape "cylinder" "float radius" [ 0.05 ] "float zmin" [ -0.25 ] "float zmax" [ 0.25 ]
AttributeEnd)";
    })->sppScale = 2;
    box("light/disk", [](Box& b) {
        b.light = R"(AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 5 5 5 ]
  Translate 0 0.95 0
  Rotate 90 1 0 0
  Shape "disk" "float radius" [ 0.22 ]
AttributeEnd)";
    })->sppScale = 2;
    box("light/triangle-mesh", [](Box& b) {
        b.light = "AttributeBegin\n  AreaLightSource \"diffuse\" \"rgb L\" [ 5 5 5 ]\n  " + triangleGrid(4, 0.2, 0.99) +
                  "\nAttributeEnd";
    });
    box("light/point", [](Box& b) {
        b.light = R"(LightSource "point" "point3 from" [ 0 0.8 0 ] "rgb I" [ 0.6 0.6 0.6 ])";
    });
    box("light/spot", [](Box& b) {
        b.light = R"(LightSource "spot" "point3 from" [ 0 0.95 0 ] "point3 to" [ 0 0 0 ] "float coneangle" [ 40 ]
  "float conedelta" [ 10 ] "rgb I" [ 1.5 1.5 1.5 ])";
    })->sppScale = 2;
    box("light/goniometric", [&](Box& b) {
        b.light = R"(AttributeBegin
  Translate 0 0.8 0
  LightSource "goniometric" "string filename" [ ")" + dir + R"(/gonio.pfm" ] "rgb I" [ 1 1 1 ]
AttributeEnd)";
    });
    box("light/projection", [&](Box& b) {
        b.light = R"(AttributeBegin
  Translate 0 0.5 1.5
  Rotate 180 0 1 0
  LightSource "projection" "string filename" [ ")" + dir + R"(/slide.pfm" ] "float fov" [ 30 ] "float scale" [ 3 ]
AttributeEnd)";
    });
    box("light/distant", [](Box& b) {
        b.light = R"(LightSource "distant" "point3 from" [ 0.3 1 3 ] "point3 to" [ 0 0.5 0 ] "rgb L" [ 2 2 2 ])";
    });
    // Many lights of every finite kind and one at infinity, chosen by each of the scene's
    // light samplers: by the receiving point ("bvh", the default: next-event estimation and
    // BDPT's s = 1 with their MIS weights), by power and uniformly. The three must agree.
    const auto manyLights = [](Box& b) {
        std::string quads;
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i) {
                const double x = -0.3 + 0.3 * i, z = -0.3 + 0.3 * j, h = 0.06;
                const double r = 1 + 2.5 * i, g = 1 + 1.5 * j, bl = 4 - i - j;
                quads += "AttributeBegin\n  AreaLightSource \"diffuse\" \"rgb L\" [ " + std::to_string(r) + " " +
                         std::to_string(g) + " " + std::to_string(bl) + " ]\n  Shape \"bilinearmesh\" \"point3 P\" [ " +
                         std::to_string(x - h) + " 0.99 " + std::to_string(z - h) + "  " + std::to_string(x + h) +
                         " 0.99 " + std::to_string(z - h) + "  " + std::to_string(x - h) + " 0.99 " +
                         std::to_string(z + h) + "  " + std::to_string(x + h) + " 0.99 " + std::to_string(z + h) +
                         " ]\nAttributeEnd\n";
            }
        b.light = quads + R"(LightSource "point" "point3 from" [ -0.35 0.3 0.2 ] "rgb I" [ 0.05 0.08 0.1 ]
LightSource "point" "point3 from" [ 0.4 0.85 -0.4 ] "rgb I" [ 0.2 0.1 0.05 ]
LightSource "point" "point3 from" [ 0.1 0.6 0.3 ] "rgb I" [ 0.02 0.02 0.02 ]
LightSource "spot" "point3 from" [ 0.3 0.9 0.3 ] "point3 to" [ -0.2 0 -0.2 ] "float coneangle" [ 25 ]
  "float conedelta" [ 8 ] "rgb I" [ 0.8 0.8 0.6 ]
AttributeBegin
  ReverseOrientation
  AreaLightSource "diffuse" "rgb L" [ 3 3 3 ]
  Shape "bilinearmesh" "point3 P" [ -0.49 0.2 -0.1   -0.49 0.2 0.1   -0.49 0.4 -0.1   -0.49 0.4 0.1 ]
AttributeEnd)";
        b.environment = R"(LightSource "distant" "point3 from" [ 0.3 1 3 ] "point3 to" [ 0 0.5 0 ] "rgb L" [ 0.5 0.5 0.5 ])";
    };
    box("light/many", manyLights)->sppScale = 2;
    Box manyBase;
    manyLights(manyBase);
    for (const char* sampler : {"power", "uniform"}) {
        Variant* var = box(std::string("light/many-") + sampler, [&](Box& b) {
            manyLights(b);
            b.integrator = std::string("\"string lightsampler\" \"") + sampler + "\"";
        });
        var->sameAs = manyBase.text();
        // Uniform choice spends most light samples on the dim lights.
        if (std::string(sampler) == "uniform") var->integratorScale = {{"path", 4}};
    }
    box(
        "light/infinite-uniform", [](Box& b) { b.environment = R"(LightSource "infinite" "rgb L" [ 0.4 0.4 0.4 ])"; },
        noLight);
    box(
        "light/infinite-image",
        [&](Box& b) {
            b.environment = R"(AttributeBegin
  Rotate -90 1 0 0
  LightSource "infinite" "string filename" [ ")" + dir + R"(/env.pfm" ]
AttributeEnd)";
        },
        noLight);

    // ---- interface shapes: they bound media and must change nothing here ----
    const std::string pointLight = R"(LightSource "point" "point3 from" [ 0 0.9 0 ] "rgb I" [ 0.6 0.6 0.6 ])";
    Box pointLit;
    pointLit.light = pointLight;
    box("interface/between-point-light-and-floor", [&](Box& b) {
        b.light = pointLight;
        b.extra = R"(AttributeBegin
  Material "interface"
  Shape "bilinearmesh" "point3 P" [ -0.5 0.8 -0.5   0.5 0.8 -0.5   -0.5 0.8 0.5   0.5 0.8 0.5 ]
AttributeEnd)";
    })->sameAs = pointLit.text();
    box("interface/in-front-of-camera", [](Box& b) {
        b.extra = R"(AttributeBegin
  Material "interface"
  Shape "bilinearmesh" "point3 P" [ -2 -2 1   2 -2 1   -2 2 1   2 2 1 ]
AttributeEnd)";
    })->sameAs = base.text();
    box("interface/box-around-sphere", [](Box& b) {
        b.extra = R"(AttributeBegin
  Material "interface"
  Translate 0 0.25 0
  Scale 0.3 0.3 0.3
  Shape "bilinearmesh" "point3 P" [ -1 -1 1  1 -1 1  -1 1 1  1 1 1 ]
  Shape "bilinearmesh" "point3 P" [ -1 -1 -1  1 -1 -1  -1 1 -1  1 1 -1 ]
  Shape "bilinearmesh" "point3 P" [ -1 -1 -1  -1 1 -1  -1 -1 1  -1 1 1 ]
  Shape "bilinearmesh" "point3 P" [ 1 -1 -1  1 1 -1  1 -1 1  1 1 1 ]
  Shape "bilinearmesh" "point3 P" [ -1 1 -1  1 1 -1  -1 1 1  1 1 1 ]
AttributeEnd)";
    })->sameAs = base.text();

    // ---- materials (the sphere's) ----
    auto material = [&](const std::string& name, const std::string& m, std::set<std::string> cannot = {}) {
        return box(
            "material/" + name, [&](Box& b) { b.objectMaterial = m; }, std::move(cannot));
    };
    material("conductor-smooth", R"(Material "conductor" "float roughness" [ 0 ])", noLight);
    material("conductor-rough", R"(Material "conductor" "spectrum eta" "metal-Au-eta" "spectrum k" "metal-Au-k"
  "float roughness" [ 0.25 ])");
    material("conductor-anisotropic", R"(Material "conductor" "float uroughness" [ 0.05 ] "float vroughness" [ 0.4 ])");
    material("dielectric-smooth", R"(Material "dielectric" "float eta" [ 1.5 ])", noLight);
    material("dielectric-rough", R"(Material "dielectric" "float eta" [ 1.5 ] "float roughness" [ 0.3 ])");
    material("dielectric-dispersive", R"(Material "dielectric" "spectrum eta" "glass-BK7")", noLight)->sppScale = 2;
    // mmlt resolved 1.9% with the matrix's bootstrap.
    material("thindielectric", R"(Material "thindielectric" "float eta" [ 1.5 ])", noLight)->bootstrapScale = {{"mmlt", 2}};
    material("coateddiffuse-smooth", R"(Material "coateddiffuse" "rgb reflectance" [ 0.6 0.3 0.2 ])", noLight);
    material("coateddiffuse-rough",
             R"(Material "coateddiffuse" "rgb reflectance" [ 0.6 0.3 0.2 ] "float roughness" [ 0.3 ])");
    material("coatedconductor",
             R"(Material "coatedconductor" "float interface.roughness" [ 0.2 ] "float conductor.roughness" [ 0.2 ])");
    material("diffusetransmission",
             R"(Material "diffusetransmission" "rgb reflectance" [ 0.4 0.4 0.4 ] "rgb transmittance" [ 0.4 0.5 0.3 ])");
    material("mix", R"(MakeNamedMaterial "a" "string type" "diffuse" "rgb reflectance" [ 0.8 0.2 0.2 ]
MakeNamedMaterial "b" "string type" "conductor" "float roughness" [ 0.2 ]
Material "mix" "string materials" [ "a" "b" ] "float amount" [ 0.4 ])");
    material("measured", "Material \"measured\" \"string filename\" [ \"" + data + "/pbrt-v4/measured/ggx-spectral.bsdf\" ]");
    // pbrt-v4's subsurface by random walk (issue 36): a rough dielectric around a chromatic,
    // forward-scattering medium about 3 mean free paths across the sphere; light enters and
    // leaves through the rough boundary, so every integrator samples it.
    material("subsurface-rough", R"(Material "subsurface" "float roughness" [ 0.3 ] "float g" [ 0.3 ]
  "rgb sigma_a" [ 0.5 1 2 ] "rgb sigma_s" [ 6 5 4 ])");

    // Hair fibres across the box, as flat curves (pbrt-v4's default type: ribbons that face
    // each ray) and as cylinder curves (the same strips, shaded as tubes). The hair BSDF needs
    // its own adjoint, and the densities there are per unit of the fibre's area
    // (hair_bxdf.cpp; densityCos in transport/path_vertex.h).
    for (const char* type : {"flat", "cylinder"})
        box(std::string("material/hair") + (std::string(type) == "flat" ? "" : "-cylinder"), [type](Box& b) {
            b.extra = std::string(R"(AttributeBegin
  Material "hair" "rgb sigma_a" [ 0.4 0.6 0.9 ]
  Shape "curve" "string type" [ "TYPE" ] "float width" [ 0.06 ]
    "point3 P" [ -0.4 0.2 0.1  -0.1 0.5 0.2  0.1 0.3 0.1  0.4 0.6 0.2 ]
  Shape "curve" "string type" [ "TYPE" ] "float width" [ 0.06 ]
    "point3 P" [ -0.4 0.7 0.0  -0.1 0.5 0.1  0.1 0.8 0.0  0.4 0.4 0.1 ]
AttributeEnd)");
            for (size_t at; (at = b.extra.find("TYPE")) != std::string::npos;) b.extra.replace(at, 4, type);
        });

    // ---- textures and cut-outs ----
    box("texture/checkerboard", [](Box& b) {
        b.floorMaterial = R"(Texture "c" "spectrum" "checkerboard" "float uscale" [ 4 ] "float vscale" [ 4 ]
  "rgb tex1" [ 0.8 0.8 0.2 ] "rgb tex2" [ 0.1 0.3 0.7 ]
Material "diffuse" "texture reflectance" "c")";
    });
    box("texture/imagemap", [&](Box& b) {
        b.floorMaterial = R"(Texture "i" "spectrum" "imagemap" "string filename" [ ")" + dir + R"(/checker.pfm" ]
Material "diffuse" "texture reflectance" "i")";
    });
    box("texture/bump", [](Box& b) {
        b.objectMaterial = R"(Texture "bumps" "float" "wrinkled" "float scale" [ 20 ]
Texture "d" "float" "scale" "texture tex" "bumps" "float scale" [ 0.01 ]
Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.8 ] "texture displacement" "d")";
    });
    box("texture/alpha-cutout", [](Box& b) {
        b.extra = R"(AttributeBegin
  Texture "holes" "float" "checkerboard" "float uscale" [ 4 ] "float vscale" [ 4 ] "float tex1" [ 1 ] "float tex2" [ 0 ]
  Material "diffuse" "rgb reflectance" [ 0.8 0.8 0.8 ]
  Shape "bilinearmesh" "point3 P" [ -0.4 0.1 0.3   0.4 0.1 0.3   -0.4 0.9 0.3   0.4 0.9 0.3 ] "texture alpha" "holes"
AttributeEnd)";
    });

    // ---- cameras ----
    box("camera/thin-lens", [](Box& b) {
        b.camera = R"(LookAt 0 0.5 2.2  0 0.5 0  0 1 0
Camera "perspective" "float fov" [ 30 ] "float lensradius" [ 0.05 ] "float focaldistance" [ 2.2 ])";
    });
    // A delta light seen in a mirror through a thin lens: its L S E paths are sampled only
    // by light subpaths that cross the lens (the t = 0 strategy of bdpt, light, pssmlt and
    // mlt; thesis §1.1, §10.2; docs/unsampled-paths.md) and show as a bokeh disk, about two
    // thirds of the image. The box's only light is a spot aimed at the mirror image of the
    // lens, so that a sixth of the light subpaths cross the lens (from an isotropic point
    // light a few in a thousand would); the rest of its cone lights the back wall around the
    // mirror, and the room by that.
    box("camera/thin-lens-delta-light-in-mirror", [](Box& b) {
        b.camera = R"(LookAt 0 0.5 2.2  0 0.5 0  0 1 0
Camera "perspective" "float fov" [ 30 ] "float lensradius" [ 0.3 ] "float focaldistance" [ 1.5 ])";
        b.light = R"(LightSource "spot" "rgb I" [ 1 1 1 ] "point3 from" [ 0.25 0.8 0.2 ] "point3 to" [ 0 0.5 -3.18 ]
  "float coneangle" [ 12 ] "float conedeltaangle" [ 3 ])";
        b.extra = R"(AttributeBegin
  Material "conductor" "rgb reflectance" [ 0.95 0.85 0.6 ] "float roughness" [ 0 ]
  Shape "bilinearmesh" "point3 P" [ 0.1 0.64 -0.49   0.3 0.64 -0.49   0.1 0.84 -0.49   0.3 0.84 -0.49 ]
AttributeEnd)";
    }, {"path", "mmlt"});
    // The box through cameras that no connection reaches: BDPT and the chains without their
    // t = 1 strategies against the path tracer.
    box("camera/orthographic", [](Box& b) {
        b.camera = R"(LookAt 0 0.5 2.2  0 0.5 0  0 1 0
Camera "orthographic" "float screenwindow" [ -0.55 0.55 -0.55 0.55 ])";
    }, lensless);
    box("camera/spherical", [](Box& b) {
        b.camera = R"(LookAt 0 0.5 0.3  0 0.5 0  0 1 0
Camera "spherical" "string mapping" "equalarea")";
    }, lensless);
    box("camera/realistic", [&](Box& b) {
        b.camera = R"(LookAt 0 0.5 2.2  0 0.5 0  0 1 0
Camera "realistic" "string lensfile" [ ")" + data + R"(/lenses/dgauss.50mm.dat" ] "float aperturediameter" [ 8 ]
  "float focusdistance" [ 2.2 ])";
        b.light = quadLight(R"("rgb L" [ 125 125 125 ])");  // the lens passes 1/25 of a pinhole's light
    }, lensless)->sppScale = 4;  // at 2, pssmlt resolved 1.9%: too close to the 2% it must
    auto exactFurnace = [&](const std::string& name, const std::string& camera, double albedo, int maxDepth,
                            std::set<std::string> cannot) {
        Variant var;
        var.name = name;
        var.scene = furnace(camera, albedo, maxDepth);
        var.exact = furnaceValue(albedo, maxDepth);
        var.cannot = std::move(cannot);
        var.spectral = false;  // the exact answer is RGB's
        var.sppScale = 2;      // 16 x 16 pixels, and light tracing's splats spread thinly
        v.push_back(var);
    };
    const std::string inside = "LookAt 0 0 0  0 0 1  0 1 0\n";
    exactFurnace("camera/pinhole-furnace", inside + R"(Camera "perspective" "float fov" [ 60 ])", 0.6, 5, {});
    exactFurnace("camera/orthographic-furnace", inside + R"(Camera "orthographic")", 0.6, 5, lensless);
    exactFurnace("camera/spherical-furnace", inside + R"(Camera "spherical" "string mapping" "equalarea")", 0.6, 5,
                 lensless);
    // The camera inside an emitter whose material is black sees exactly its emission.
    exactFurnace("light/inside-black-emitter", inside + R"(Camera "perspective" "float fov" [ 60 ])", 0, 5, {});
    // ---- participating media ----
    // The same emitter filled with fog of albedo 1 (coloured, forward-scattering) around the
    // camera: scattering only redistributes the wall's radiance, so the image is still L. At
    // most 1.5 optical radii, paths past maxdepth 30 are negligible (each scattering keeps a
    // path in the sphere with probability below 0.6). Every integrator runs it but light
    // tracing, whose connections from scattering points around the lens have unbounded
    // variance (coverage.h); Veach's mlt's lens vertex is then in the fog.
    exactFurnace("medium/fog-furnace",
                 R"(MakeNamedMedium "fog" "string type" "homogeneous" "rgb sigma_a" [ 0 0 0 ]
  "rgb sigma_s" [ 0.15 0.3 0.5 ] "float g" [ 0.5 ]
MediumInterface "" "fog"
)" + inside + R"(Camera "perspective" "float fov" [ 60 ])",
                 0, 30, {"light"});
    v.back().integratorScale = {{"mlt", 2}};  // at 1, mlt resolved 2.1%
    // mmlt resolved 1.5-2.3% with the matrix's bootstrap and 2.0% with twice the mutations,
    // 1.8% with 3 or 5 times the bootstrap alone: twice both.
    // mlt keeps the bootstrap it had before its stratification (15000): at 5000 it resolved
    // 1.9% (1.5% at 15000); its samples' variance here is past the stratified first numbers.
    v.back().bootstrapScale = {{"mmlt", 2}, {"mlt", 3}};
    v.back().integratorScale["mmlt"] = 2;
    // Fog filling the base box (camera outside it, in vacuum: the box's open side is an
    // `interface` face): chromatic scattering and absorption, connections through the medium
    // and medium vertices in every strategy.
    box("medium/fog", [](Box& b) {
        b.maxDepth = 4;
        // The light is in the fog: a light subpath starts there (pbrt-v4: the light's medium
        // is the MediumInterface's outside at its definition).
        b.light = "AttributeBegin\nMediumInterface \"fog\" \"fog\"\n" + b.light + "\nAttributeEnd";
        b.extra = R"(MakeNamedMedium "fog" "string type" "homogeneous" "rgb sigma_a" [ 0.1 0.2 0.3 ]
  "rgb sigma_s" [ 0.8 0.5 0.3 ] "float g" [ 0.3 ]
AttributeBegin
  Material "interface"
  MediumInterface "fog" ""
  Shape "bilinearmesh" "point3 P" [ -0.5 0 0.5   0.5 0 0.5   -0.5 1 0.5   0.5 1 0.5 ]
AttributeEnd)";
    })->bootstrapScale = {{"pssmlt", 3}, {"mmlt", 2}};  // with the matrix's: 2.5% and 1.8%

    // The same fog glowing (pbrt-v4's sigma_a Le, a third of the image): emission found by the
    // camera walk's free flights alone, the s = 0 strategies of bdpt, pssmlt and mmlt with
    // weight 1. Light tracing and Veach's mlt have no strategy for it (coverage.h).
    box("medium/emissive", [](Box& b) {
        b.maxDepth = 4;
        b.light = "AttributeBegin\nMediumInterface \"fog\" \"fog\"\n" + b.light + "\nAttributeEnd";
        b.extra = R"(MakeNamedMedium "fog" "string type" "homogeneous" "rgb sigma_a" [ 0.1 0.2 0.3 ]
  "rgb sigma_s" [ 0.8 0.5 0.3 ] "float g" [ 0.3 ] "rgb Le" [ 1.5 1 0.8 ]
AttributeBegin
  Material "interface"
  MediumInterface "fog" ""
  Shape "bilinearmesh" "point3 P" [ -0.5 0 0.5   0.5 0 0.5   -0.5 1 0.5   0.5 1 0.5 ]
AttributeEnd)";
    }, {"light", "mlt"});

    // The same with a 2 x 2 x 2 density grid: null collisions in both walks' delta tracking and
    // in every connection's ratio tracking, against one chromatic majorant.
    box("medium/grid-fog", [](Box& b) {
        b.maxDepth = 4;
        b.light = "AttributeBegin\nMediumInterface \"fog\" \"fog\"\n" + b.light + "\nAttributeEnd";
        b.extra = R"(MakeNamedMedium "fog" "string type" "uniformgrid" "integer nx" [ 2 ] "integer ny" [ 2 ] "integer nz" [ 2 ]
  "float density" [ 0.2 1.5 0.6 1 1.2 0.3 0.8 0.5 ] "point3 p0" [ -0.5 0 -0.5 ] "point3 p1" [ 0.5 1 0.5 ]
  "rgb sigma_a" [ 0.1 0.2 0.3 ] "rgb sigma_s" [ 0.8 0.5 0.3 ] "float g" [ -0.2 ]
AttributeBegin
  Material "interface"
  MediumInterface "fog" ""
  Shape "bilinearmesh" "point3 P" [ -0.5 0 0.5   0.5 0 0.5   -0.5 1 0.5   0.5 1 0.5 ]
AttributeEnd)";
    })->sppScale = 2;  // at 1, pssmlt resolved 2.0%

    // The same with pbrt-v4's procedural cloud filling the box: Perlin-noise density over a
    // solid base, tracked against its 16^3 majorant grid (DDA walks in every flight and
    // connection).
    box("medium/cloud", [](Box& b) {
        b.maxDepth = 4;
        b.light = "AttributeBegin\nMediumInterface \"fog\" \"fog\"\n" + b.light + "\nAttributeEnd";
        b.extra = R"(MakeNamedMedium "fog" "string type" "cloud" "float density" [ 1 ] "float frequency" [ 3 ]
  "point3 p0" [ -0.5 0 -0.5 ] "point3 p1" [ 0.5 1 0.5 ]
  "rgb sigma_a" [ 0.1 0.2 0.3 ] "rgb sigma_s" [ 1.2 0.8 0.5 ] "float g" [ 0.3 ]
AttributeBegin
  Material "interface"
  MediumInterface "fog" ""
  Shape "bilinearmesh" "point3 P" [ -0.5 0 0.5   0.5 0 0.5   -0.5 1 0.5   0.5 1 0.5 ]
AttributeEnd)";
    });  // at 2 (the suite's longest cell, 144 test-s) every integrator resolved 1.1% or better

    // ---- path depth ----
    box("depth/0", [](Box& b) { b.maxDepth = 0; })->sppScale = 8;
    box("depth/1", [](Box& b) { b.maxDepth = 1; })->sppScale = 4;
    box("depth/large", [](Box& b) { b.maxDepth = 100; });

    // ---- the other colour mode ----
    for (const char* name : {"base", "light/sphere-black-material", "material/dielectric-smooth",
                             "interface/box-around-sphere"}) {
        for (size_t i = 0; i < v.size(); ++i)
            if (v[i].name == name) {
                Variant rgb = v[i];
                rgb.name = std::string("rgb/") + name;
                rgb.spectral = false;
                v.push_back(rgb);
                break;
            }
    }
    return v;
}

}  // namespace ps::test
