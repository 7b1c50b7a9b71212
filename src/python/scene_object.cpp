#include "python/scene_object.h"

#include "render/scene_builder.h"
#include "util/error.h"

namespace ps::python {

Scene& SceneObject::prepare(bool spectral) {
    if (!built_ || builtSpectral_ != spectral) {
        built_.reset();  // one built scene at a time: its meshes may be large
        const HeldWarnings inFileOrder;
        built_ = buildScene(desc_, spectral);
        builtSpectral_ = spectral;
        settings_ = built_->settings();
        bounds_ = built_->pixelBounds();
    } else {
        built_->settings() = settings_;
        built_->setPixelBounds(bounds_);
    }
    return *built_;
}

}  // namespace ps::python
