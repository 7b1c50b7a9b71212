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

// The same emitting sphere filled with fog around the camera: a scene with media, where
// path is volpath and only --mis balance applies.
inline const char* kFogFurnace = R"(LookAt 0 0 0  0 0 1  0 1 0
MakeNamedMedium "fog" "string type" "homogeneous" "rgb sigma_a" [ 0.1 0.1 0.1 ] "rgb sigma_s" [ 0.2 0.2 0.2 ]
MediumInterface "" "fog"
Camera "perspective" "float fov" [ 60 ]
Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ]
WorldBegin
AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]
ReverseOrientation
Shape "sphere" "float radius" [ 1 ]
)";

}  // namespace ps::test
