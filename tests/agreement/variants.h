// The agreement matrix's scenes: a small box and one-feature variants of it (docs/agreement-matrix.md
// lists them). Each variant is rendered by every integrator that can sample it and compared
// with a reference that trusts no single integrator: an exact answer, the same scene without
// the feature where the feature must not change the image, or the median of the others.
#pragma once
#include <map>
#include <set>
#include <string>
#include <vector>

namespace ps::test {

struct Variant {
    std::string name;    // "family/feature"
    std::string scene;   // the scene's text
    // Where the feature must not change the image: the scene without it, rendered by path and
    // bdpt (whose agreement the base variant checks). Empty: none.
    std::string sameAs;
    double exact = -1;   // >= 0: every pixel's exact luminance
    // The integrators that cannot sample the variant (transport/coverage.h must say so, and
    // they are left out): a change in coverage shows as a failure here.
    std::set<std::string> cannot;
    bool spectral = true;  // --color spectral (the renderer's default) or rgb
    int sppScale = 1;      // the variant's samples per pixel over the matrix's
    std::map<std::string, int> integratorScale;  // and one integrator's over that
    // A Metropolis integrator's bootstrap over the matrix's (its b's error is the image mean's).
    std::map<std::string, int> bootstrapScale;
    // Open bugs the matrix found: integrator -> what is wrong. Such a cell must still differ
    // (it fails once the bug is fixed, so that the marker goes with it).
    std::map<std::string, std::string> knownBias;
};

// Every variant, in the order docs/agreement-matrix.md lists them. Files the scenes read
// (image textures, the environment map, the goniometric and projection images) are written
// under `dataDir`, which the scenes name by absolute path.
std::vector<Variant> agreementVariants(const std::string& dataDir);

// A name gtest accepts: letters, digits and '_' ("light/area-two-sided" -> "light_area_two_sided").
std::string testName(const std::string& variant);

}  // namespace ps::test
