#include "spectral/named_spectra.h"
#include "spectral/illuminant_data.h"
#include "spectral/optical_constants_data.h"

namespace ps {

std::optional<SpectrumSource> namedSpectrum(const std::string& name) {
    if (auto pairs = standardIlluminantPairs(name); !pairs.empty())
        return SpectrumSource::piecewiseLinear(PiecewiseLinearTable::fromInterleaved(pairs, true));
    if (auto pairs = opticalConstantPairs(name); !pairs.empty())
        return SpectrumSource::piecewiseLinear(PiecewiseLinearTable::fromInterleaved(pairs, false));
    return std::nullopt;
}

}  // namespace ps
