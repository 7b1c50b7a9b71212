// Lens description files of the realistic camera (pbrt-v4's format): whitespace-separated
// numbers, '#' starting a comment, four per interface from the scene side to the film side:
// curvature radius, thickness (distance to the next interface, or to the film for the
// last), index of refraction of the medium behind the interface (towards the film), and
// aperture diameter, lengths in millimetres. A radius of 0 is the aperture stop (a plane).
#pragma once
#include <string>
#include <vector>

namespace ps {

// One interface, lengths converted to metres (scene units).
struct LensInterface {
    float curvatureRadius = 0;  // 0: the aperture stop
    float thickness = 0;
    float eta = 1;              // 0 in a file means air, as on the stop's row
    float apertureRadius = 0;
    bool isStop() const { return curvatureRadius == 0; }
};

// Parses `text`; `name` is used in messages. Throws InputError "name:line: ..." for a value
// that is not a number, a count of numbers that is not a multiple of four (naming the line
// of the incomplete row), a non-finite value, a negative thickness, index or diameter,
// or an empty description.
std::vector<LensInterface> parseLensDescription(const std::string& text, const std::string& name);
// Reads and parses the file (InputError "path: cannot open lens file: ..." if unreadable).
std::vector<LensInterface> readLensFile(const std::string& path);

}  // namespace ps
