// A scene of many lights for statistical render tests (shadow-ray roulette, light-sample
// splitting, the figures per technique).
#pragma once
#include <cmath>
#include <sstream>
#include <string>

namespace ps::test {

// A floor and two walls under 40 small lights of radiances over two orders of magnitude at
// heights from 0.3 to 3, a point light and a dim sky: most connections carry little, a few
// much.
inline std::string manyLightsScene() {
    std::ostringstream s;
    s << R"(
        LookAt 0 3 -4  0 0 0.5  0 1 0
        Camera "perspective" "float fov" [ 60 ]
        Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ]
        Sampler "sobol"
        Integrator "path" "integer maxdepth" [ 3 ]
        WorldBegin
        LightSource "infinite" "rgb L" [ 0.05 0.05 0.08 ]
        LightSource "point" "point3 from" [ 0 1.2 0.3 ] "rgb I" [ 0.8 0.6 0.3 ]
        Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
        Shape "trianglemesh" "point3 P" [ -3 0 -3  3 0 -3  3 0 3  -3 0 3 ] "integer indices" [ 0 1 2 0 2 3 ]
        Material "diffuse" "rgb reflectance" [ 0.6 0.3 0.2 ]
        Shape "trianglemesh" "point3 P" [ -3 0 3  3 0 3  3 3 3  -3 3 3 ] "integer indices" [ 0 1 2 0 2 3 ]
        Shape "trianglemesh" "point3 P" [ 3 0 -3  3 0 3  3 3 3  3 3 -3 ] "integer indices" [ 0 1 2 0 2 3 ]
    )";
    for (int i = 0; i < 40; ++i) {
        const float x = -2.5f + 5.0f * float((i * 7) % 40) / 40, z = -2.5f + 5.0f * float((i * 13) % 40) / 40;
        const float h = 0.3f + 2.7f * float((i * 11) % 40) / 40, L = 0.2f * std::pow(100.0f, float((i * 3) % 40) / 40);
        s << "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ " << L << " " << 0.8f * L << " " << 0.6f * L
          << " ]\nTranslate " << x << " " << h << " " << z << "\n"
          << "Shape \"trianglemesh\" \"point3 P\" [ -0.1 0 -0.1  0.1 0 -0.1  0.1 0 0.1  -0.1 0 0.1 ]"
             " \"integer indices\" [ 0 3 2 0 2 1 ]\nAttributeEnd\n";
    }
    return s.str();
}

}  // namespace ps::test
