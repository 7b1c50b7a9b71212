// ParamSet lookups with pbrt-v4's rules (PBRT-CONVENTIONS §8 Parameters): a lookup matches
// name and type; a parameter of another type is left unused (and reported later), while a
// matching one with the wrong number of values is an error.
#include "scene/params.h"

#include <algorithm>
#include "scene/color_space.h"

#include "scene/spectra.h"
#include "spectral/named_spectra.h"
#include "util/path.h"

namespace ps {

namespace {

std::string describe(const Param& p) { return "\"" + p.typeName + " " + p.name + "\""; }

const Param* findTyped(const ParamSet& ps, const std::string& name, ParamType type) {
    const Param* p = ps.find(name);
    if (!p || p->type != type) return nullptr;  // wrong type: left unused, reported later
    p->used = true;
    return p;
}

void expectCount(const Param& p, size_t want, size_t have) {
    if (have != want)
        throw InputError(p.loc, "parameter " + describe(p) + " needs " + std::to_string(want) + " value" +
                                    (want == 1 ? "" : "s") + ", got " + std::to_string(have));
}

void expectMultiple(const Param& p, size_t per) {
    if (p.numbers.empty() || p.numbers.size() % per != 0)
        throw InputError(p.loc, "parameter " + describe(p) + ": the number of values (" + std::to_string(p.numbers.size()) +
                                    ") is not a positive multiple of " + std::to_string(per));
}

std::vector<Vec3> triples(const Param& p) {
    expectMultiple(p, 3);
    std::vector<Vec3> out(p.numbers.size() / 3);
    for (size_t i = 0; i < out.size(); ++i)
        out[i] = Vec3(float(p.numbers[3 * i]), float(p.numbers[3 * i + 1]), float(p.numbers[3 * i + 2]));
    return out;
}

Spectrum rgbValue(const Param& p, SpectrumKind kind, const RGBColorSpace* space) {
    expectCount(p, 3, p.numbers.size());
    Spectrum s(float(p.numbers[0]), float(p.numbers[1]), float(p.numbers[2]));
    if (s.r < 0 || s.g < 0 || s.b < 0) throw InputError(p.loc, "parameter " + describe(p) + " has a negative component");
    // pbrt-v4 refuses RGB reflectances above 1 rather than clamping them (§6).
    if (kind == SpectrumKind::Albedo && s.maxComponent() > 1)
        throw InputError(p.loc, "parameter " + describe(p) + " is a reflectance and has a component > 1 (pbrt-v4 requires [0, 1])");
    return toRenderingSpace(s, space, kind);
}

Spectrum blackbodyValue(const Param& p, SpectrumKind kind) {
    if (p.numbers.size() == 2)
        throw InputError(p.loc, "parameter " + describe(p) + " has two values: that is pbrt-v3's [kelvin scale] form; "
                                "pbrt-v4 takes one temperature (use \"float scale\"; `pbrt --upgrade` converts it)");
    expectCount(p, 1, p.numbers.size());
    if (!(p.numbers[0] > 0)) throw InputError(p.loc, "parameter " + describe(p) + ": the temperature must be positive");
    return blackbodyToRGB(float(p.numbers[0]), kind);
}

// The (wavelength, value) pairs of an inline or file spectrum; false for a named one.
bool spectrumSamples(const Param& p, const std::string& baseDirectory, std::vector<float>& lambda, std::vector<float>& value) {
    lambda.clear();
    value.clear();
    if (!p.strings.empty()) {
        expectCount(p, 1, p.strings.size());
        const std::string& name = p.strings[0];
        if (namedSpectrumToRGB(name, SpectrumKind::Unbounded)) return false;
        std::string err = readSpectrumFile(resolvePath(baseDirectory, name), lambda, value);
        if (!err.empty())
            throw InputError(p.loc, "parameter " + describe(p) + ": \"" + name +
                                        "\" is not a named spectrum and not a readable spectrum file (" + err + ")");
    } else {
        if (p.numbers.empty() || p.numbers.size() % 2 != 0)
            throw InputError(p.loc, "parameter " + describe(p) + " needs wavelength/value pairs, got " +
                                        std::to_string(p.numbers.size()) + " values");
        for (size_t i = 0; i < p.numbers.size(); i += 2) {
            if (!lambda.empty() && p.numbers[i] <= lambda.back())
                throw InputError(p.loc, "parameter " + describe(p) + ": wavelengths must increase (" +
                                            std::to_string(lambda.back()) + " is followed by " + std::to_string(p.numbers[i]) + ")");
            lambda.push_back(float(p.numbers[i]));
            value.push_back(float(p.numbers[i + 1]));
        }
    }
    return true;
}

Spectrum spectrumValue(const Param& p, SpectrumKind kind, const std::string& baseDirectory) {
    std::vector<float> lambda, value;
    if (!spectrumSamples(p, baseDirectory, lambda, value)) return *namedSpectrumToRGB(p.strings[0], kind);
    if (p.strings.empty() && lambda.size() == 1) warning(p.loc, "spectrum " + describe(p) + " is non-zero at a single wavelength only");
    return sampledSpectrumToRGB(lambda, value, kind);
}

}  // namespace

void ParamSet::add(Param p) {
    for (Param& q : params)
        if (q.name == p.name) {
            q = std::move(p);
            return;
        }
    params.push_back(std::move(p));
}

void ParamSet::addDefault(Param p) {
    if (!has(p.name)) params.push_back(std::move(p));
}

const Param* ParamSet::find(const std::string& name) const {
    if (std::find(asked.begin(), asked.end(), name) == asked.end()) asked.push_back(name);
    for (const Param& p : params)
        if (p.name == name) return &p;
    return nullptr;
}

namespace {

// Levenshtein distance: insertions, deletions and substitutions of one character.
size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        size_t diagonal = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diagonal = up;
        }
    }
    return row[b.size()];
}

}  // namespace

float ParamSet::getFloat(const std::string& name, float def) const {
    const Param* p = findTyped(*this, name, ParamType::Float);
    if (!p) return def;
    expectCount(*p, 1, p->numbers.size());
    return float(p->numbers[0]);
}

int ParamSet::getInt(const std::string& name, int def) const {
    const Param* p = findTyped(*this, name, ParamType::Integer);
    if (!p) return def;
    expectCount(*p, 1, p->numbers.size());
    return int(p->numbers[0]);
}

bool ParamSet::getBool(const std::string& name, bool def) const {
    const Param* p = findTyped(*this, name, ParamType::Bool);
    if (!p) return def;
    expectCount(*p, 1, p->bools.size());
    return p->bools[0];
}

std::string ParamSet::getString(const std::string& name, const std::string& def) const {
    const Param* p = findTyped(*this, name, ParamType::String);
    if (!p) return def;
    expectCount(*p, 1, p->strings.size());
    return p->strings[0];
}

Vec3 ParamSet::getPoint3(const std::string& name, Vec3 def) const {
    const Param* p = findTyped(*this, name, ParamType::Point3);
    if (!p) return def;
    expectCount(*p, 3, p->numbers.size());
    return triples(*p)[0];
}

Vec3 ParamSet::getVector3(const std::string& name, Vec3 def) const {
    const Param* p = findTyped(*this, name, ParamType::Vector3);
    if (!p) return def;
    expectCount(*p, 3, p->numbers.size());
    return triples(*p)[0];
}

std::vector<float> ParamSet::getFloats(const std::string& name) const {
    const Param* p = findTyped(*this, name, ParamType::Float);
    if (!p) return {};
    return std::vector<float>(p->numbers.begin(), p->numbers.end());
}

std::vector<int> ParamSet::getInts(const std::string& name) const {
    const Param* p = findTyped(*this, name, ParamType::Integer);
    if (!p) return {};
    return std::vector<int>(p->numbers.begin(), p->numbers.end());  // the parser checked the range
}

std::vector<std::string> ParamSet::getStrings(const std::string& name) const {
    const Param* p = findTyped(*this, name, ParamType::String);
    return p ? p->strings : std::vector<std::string>{};
}

std::vector<Vec2> ParamSet::getPoint2s(const std::string& name) const {
    const Param* p = findTyped(*this, name, ParamType::Point2);
    if (!p) return {};
    expectMultiple(*p, 2);
    std::vector<Vec2> out(p->numbers.size() / 2);
    for (size_t i = 0; i < out.size(); ++i) out[i] = Vec2(float(p->numbers[2 * i]), float(p->numbers[2 * i + 1]));
    return out;
}

std::vector<Vec3> ParamSet::getPoint3s(const std::string& name) const {
    const Param* p = findTyped(*this, name, ParamType::Point3);
    return p ? triples(*p) : std::vector<Vec3>{};
}

std::vector<Vec3> ParamSet::getNormals(const std::string& name) const {
    const Param* p = findTyped(*this, name, ParamType::Normal);
    return p ? triples(*p) : std::vector<Vec3>{};
}

std::vector<Vec3> ParamSet::getVector3s(const std::string& name) const {
    const Param* p = findTyped(*this, name, ParamType::Vector3);
    return p ? triples(*p) : std::vector<Vec3>{};
}

std::optional<Spectrum> ParamSet::getSpectrum(const std::string& name, SpectrumKind kind) const {
    const Param* p = find(name);
    if (!p) return std::nullopt;
    switch (p->type) {
        case ParamType::RGB: p->used = true; return rgbValue(*p, kind, colorSpace);
        case ParamType::Blackbody: p->used = true; return blackbodyValue(*p, kind);
        case ParamType::Spectrum: p->used = true; return spectrumValue(*p, kind, baseDirectory);
        default: return std::nullopt;  // another type: unused, reported later
    }
}

std::optional<SpectrumSource> ParamSet::getSpectrumSource(const std::string& name, SpectrumKind kind) const {
    const Param* p = find(name);
    if (!p) return std::nullopt;
    switch (p->type) {
        case ParamType::RGB: {
            rgbValue(*p, kind, colorSpace);  // the same checks (count, sign, albedo <= 1)
            p->used = true;
            const RGBColorSpace& space = colorSpace ? *colorSpace : srgbColorSpace();
            const std::array<float, 3> rgb{float(p->numbers[0]), float(p->numbers[1]), float(p->numbers[2])};
            if (kind == SpectrumKind::Albedo) return SpectrumSource::rgbAlbedo(space, rgb);
            if (kind == SpectrumKind::Unbounded) return SpectrumSource::rgbUnbounded(space, rgb);
            return SpectrumSource::rgbIlluminant(space, rgb);
        }
        case ParamType::Blackbody:
            blackbodyValue(*p, kind);
            p->used = true;
            return SpectrumSource::blackbody(float(p->numbers[0]));
        case ParamType::Spectrum: {
            p->used = true;
            std::vector<float> lambda, value;
            if (!spectrumSamples(*p, baseDirectory, lambda, value)) return namedSpectrum(p->strings[0]);
            return SpectrumSource::piecewiseLinear(std::move(lambda), std::move(value));
        }
        default: return std::nullopt;
    }
}

bool ParamSet::spectrallyVarying(const std::string& name) const {
    const Param* p = find(name);
    if (!p) return false;
    switch (p->type) {
        case ParamType::RGB: return p->numbers.size() == 3 && (p->numbers[0] != p->numbers[1] || p->numbers[1] != p->numbers[2]);
        case ParamType::Blackbody: return true;
        case ParamType::Spectrum: {
            std::vector<float> lambda, value;
            // pbrt-v4's named spectra (glasses, metals, illuminants) all vary with wavelength.
            return !spectrumSamples(*p, baseDirectory, lambda, value) || !sampledSpectrumIsConstant(lambda, value);
        }
        default: return false;
    }
}

std::string ParamSet::getTexture(const std::string& name) const {
    const Param* p = findTyped(*this, name, ParamType::Texture);
    if (!p) return "";
    expectCount(*p, 1, p->strings.size());
    return p->strings[0];
}

void ParamSet::reportUnused(const std::string& context) const {
    // ps::warning prints each distinct message once, so repeated reports stay quiet.
    for (const Param& p : params) {
        if (p.used || p.fromAttribute) continue;
        // The nearest name the directive knows, if it is a likely misspelling of this one.
        std::string nearest;
        size_t best = std::max<size_t>(1, p.name.size() / 3) + 1;
        for (const std::string& known : asked)
            if (known != p.name)
                if (const size_t d = editDistance(p.name, known); d < best) {
                    best = d;
                    nearest = known;
                }
        warning(p.loc, "unused parameter " + describe(p) + " in " + context +
                           (nearest.empty() ? "" : " (did you mean \"" + nearest + "\"?)"));
    }
}

}  // namespace ps
