// A closed furnace that every Metropolis integrator renders, Veach's mlt included (the sky
// scene has an infinite light, which mlt does not support): a sphere lit from inside, every
// pixel exactly Le (1 - 0.6^6) / 0.4 at maxdepth 5 (render/mlt_scenes.h adds its Integrator
// line).
#pragma once

#include <cmath>

namespace ps::test {

inline const char* kFurnace = R"(LookAt 0 0 0  0 0 1  0 1 0
Camera "perspective" "float fov" [ 60 ]
Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
PixelFilter "box"
WorldBegin
AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]
Material "diffuse" "rgb reflectance" [ 0.6 0.6 0.6 ]
ReverseOrientation
Shape "sphere" "float radius" [ 1 ]
)";
inline const double kFurnaceValue = (1 - std::pow(0.6, 6)) / 0.4;

}  // namespace ps::test
