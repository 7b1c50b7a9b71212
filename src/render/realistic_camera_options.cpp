#include "render/realistic_camera_options.h"

#include "image/image.h"
#include "util/path.h"

namespace ps {

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
    if (!aperture.empty()) {
        ApertureMask mask;
        if (!ApertureMask::builtin(aperture, &mask))
            mask = ApertureMask::fromImage(
                readNamedBy(locOf("aperture"), [&] { return readImage(resolvePath(baseDirectory, aperture)); }));
        lp.mask = std::make_shared<const ApertureMask>(std::move(mask));
    }
    auto lens = readNamedBy(cameraLoc, [&] {
        try {
            return std::make_shared<const LensSystem>(std::move(lp));
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
