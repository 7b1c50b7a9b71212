#include "render/realistic_camera_options.h"

#include <map>
#include <mutex>
#include <sstream>

#include "image/image.h"
#include "util/path.h"

namespace ps {

namespace {

// Lens systems built in this process, by everything that determines them: the exit-pupil
// search traces tens of millions of rays, so a scene rendered again (several renders of one
// scene, the same camera in several files) reuses it. Aperture images are not cached (a
// file may change between loads); built-in shapes are named.
std::shared_ptr<const LensSystem> cachedLensSystem(const LensSystem::Params& p, const std::string& maskName,
                                                   bool cacheable) {
    if (!cacheable) return std::make_shared<const LensSystem>(p);
    std::ostringstream key;
    key.precision(9);
    for (const LensInterface& e : p.interfaces)
        key << e.curvatureRadius << ' ' << e.thickness << ' ' << e.eta << ' ' << e.apertureRadius << ';';
    key << p.apertureDiameter << ' ' << p.focusDistance << ' ' << p.filmDiagonal << ' ' << p.xRes << ' ' << p.yRes
        << ' ' << p.pupilSamplesPerSegment << ' ' << maskName;
    static std::mutex mutex;
    static std::map<std::string, std::shared_ptr<const LensSystem>> cache;
    std::lock_guard<std::mutex> lock(mutex);
    auto it = cache.find(key.str());
    if (it != cache.end()) return it->second;
    if (cache.size() >= 16) cache.clear();  // a bound on memory for long test processes
    auto lens = std::make_shared<const LensSystem>(p);
    cache.emplace(key.str(), lens);
    return lens;
}

}  // namespace

std::shared_ptr<const LensSystem> createLensSystem(const ParamSet& ps, const SourceLoc& cameraLoc,
                                                   const std::string& baseDirectory, float filmDiagonalMm, int xRes,
                                                   int yRes) {
    auto locOf = [&](const char* name) {
        const Param* p = ps.find(name);
        return p ? p->loc : cameraLoc;
    };
    const std::string file = ps.getString("lensfile", "");
    if (file.empty()) throw InputError(cameraLoc, "Camera \"realistic\": no \"lensfile\" given");
    LensSystem::Params lp;
    lp.interfaces = readNamedBy(cameraLoc, [&] { return readLensFile(resolvePath(baseDirectory, file)); });
    const float diameterMm = ps.getFloat("aperturediameter", 1.0f);
    lp.apertureDiameter = diameterMm / 1000;
    lp.focusDistance = ps.getFloat("focusdistance", 10.0f);
    lp.filmDiagonal = filmDiagonalMm / 1000;
    lp.xRes = xRes;
    lp.yRes = yRes;
    if (!(diameterMm > 0))
        throw InputError(locOf("aperturediameter"), "Camera \"realistic\": \"aperturediameter\" must be positive");
    if (!(lp.focusDistance > 0) || !std::isfinite(lp.focusDistance))
        throw InputError(locOf("focusdistance"), "Camera \"realistic\": \"focusdistance\" must be positive");
    if (!(lp.filmDiagonal > 0) || !std::isfinite(lp.filmDiagonal))
        throw InputError(cameraLoc, "Camera \"realistic\": the Film's \"diagonal\" must be positive");

    const std::string aperture = ps.getString("aperture", "");
    bool cacheable = true;
    if (!aperture.empty()) {
        ApertureMask mask;
        if (!ApertureMask::builtin(aperture, &mask)) {
            mask = ApertureMask::fromImage(
                readNamedBy(locOf("aperture"), [&] { return readImage(resolvePath(baseDirectory, aperture)); }));
            cacheable = false;
        }
        lp.mask = std::make_shared<const ApertureMask>(std::move(mask));
    }
    auto lens = readNamedBy(cameraLoc, [&] {
        try {
            return cachedLensSystem(lp, aperture, cacheable);
        } catch (const InputError& e) {
            throw InputError("Camera \"realistic\" with \"" + file + "\": " + e.what());
        }
    });
    if (lens->apertureClamped())
        warning(locOf("aperturediameter"), "Camera \"realistic\": \"aperturediameter\" " + std::to_string(diameterMm) +
                                               " mm is larger than the lens's aperture stop; clamped to the stop");
    return lens;
}

}  // namespace ps
