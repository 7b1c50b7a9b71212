#include "scene/params.h"

#include <filesystem>
#include <fstream>

#include "scene/spectra.h"
#include "util/path.h"

namespace ps {

namespace {

const Param* findTyped(const ParamSet& ps, const std::string& name, ParamType type) {
    const Param* p = ps.find(name);
    if (!p || p->type != type) return nullptr;  // wrong type: left unused, reported later
    p->used = true;
    return p;
}

void expectCount(const Param& p, size_t n, size_t have) {
    if (have != n)
        throw InputError(p.loc, "parameter \"" + p.typeName + " " + p.name + "\" needs " + std::to_string(n) +
                                    " value(s), got " + std::to_string(have));
}

std::vector<Vec3> triples(const Param& p) {
    if (p.numbers.size() % 3 != 0)
        throw InputError(p.loc, "parameter \"" + p.typeName + " " + p.name + "\": number of values is not a multiple of 3");
    std::vector<Vec3> out(p.numbers.size() / 3);
    for (size_t i = 0; i < out.size(); ++i)
        out[i] = Vec3(float(p.numbers[3 * i]), float(p.numbers[3 * i + 1]), float(p.numbers[3 * i + 2]));
    return out;
}

Spectrum spectrumFromFile(const Param& p, const std::string& file, const std::string& base, SpectrumKind kind) {
    std::ifstream in(resolvePath(base, file));
    if (!in) throw InputError(p.loc, "spectrum \"" + file + "\" is neither a named spectrum nor a readable file");
    std::vector<float> lambda, value;
    double l, v;
    while (in >> l >> v) {
        if (!lambda.empty() && l <= lambda.back())
            throw InputError(p.loc, "spectrum file \"" + file + "\": wavelengths must increase");
        lambda.push_back(float(l));
        value.push_back(float(v));
    }
    if (lambda.empty()) throw InputError(p.loc, "spectrum file \"" + file + "\" holds no wavelength/value pairs");
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
    for (const Param& p : params)
        if (p.name == name) return &p;
    return nullptr;
}

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
    return std::vector<int>(p->numbers.begin(), p->numbers.end());
}

std::vector<std::string> ParamSet::getStrings(const std::string& name) const {
    const Param* p = findTyped(*this, name, ParamType::String);
    return p ? p->strings : std::vector<std::string>{};
}

std::vector<Vec2> ParamSet::getPoint2s(const std::string& name) const {
    const Param* p = findTyped(*this, name, ParamType::Point2);
    if (!p) return {};
    if (p->numbers.size() % 2 != 0)
        throw InputError(p->loc, "parameter \"point2 " + name + "\": number of values is not a multiple of 2");
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

std::optional<Spectrum> ParamSet::getSpectrum(const std::string& name, SpectrumKind kind) const {
    const Param* p = find(name);
    if (!p) return std::nullopt;
    if (p->type == ParamType::RGB) {
        p->used = true;
        expectCount(*p, 3, p->numbers.size());
        Spectrum s(float(p->numbers[0]), float(p->numbers[1]), float(p->numbers[2]));
        if (s.r < 0 || s.g < 0 || s.b < 0)
            throw InputError(p->loc, "parameter \"rgb " + name + "\": negative RGB values are not allowed");
        if (kind == SpectrumKind::Albedo && s.maxComponent() > 1)
            throw InputError(p->loc, "parameter \"rgb " + name + "\": a reflectance must lie in [0, 1] (as pbrt-v4 requires)");
        return s;
    }
    if (p->type == ParamType::Blackbody) {
        p->used = true;
        if (p->numbers.size() == 2)
            throw InputError(p->loc, "\"blackbody " + name + "\" takes one temperature in pbrt-v4 (the two-value form is pbrt-v3 syntax)");
        expectCount(*p, 1, p->numbers.size());
        if (!(p->numbers[0] > 0)) throw InputError(p->loc, "\"blackbody " + name + "\": temperature must be positive");
        return blackbodyToRGB(float(p->numbers[0]));
    }
    if (p->type == ParamType::Spectrum) {
        p->used = true;
        if (!p->strings.empty()) {
            expectCount(*p, 1, p->strings.size());
            if (auto s = namedSpectrumToRGB(p->strings[0], kind)) return *s;
            return spectrumFromFile(*p, p->strings[0], baseDirectory, kind);
        }
        if (p->numbers.size() < 2 || p->numbers.size() % 2 != 0)
            throw InputError(p->loc, "\"spectrum " + name + "\" needs wavelength/value pairs");
        std::vector<float> lambda, value;
        for (size_t i = 0; i < p->numbers.size(); i += 2) {
            if (!lambda.empty() && p->numbers[i] <= lambda.back())
                throw InputError(p->loc, "\"spectrum " + name + "\": wavelengths must increase");
            lambda.push_back(float(p->numbers[i]));
            value.push_back(float(p->numbers[i + 1]));
        }
        Spectrum s = sampledSpectrumToRGB(lambda, value, kind);
        if (kind == SpectrumKind::Albedo) s = clamp(s, 0, 1);
        return s;
    }
    return std::nullopt;  // another type: unused, reported later
}

std::string ParamSet::getTexture(const std::string& name) const {
    const Param* p = findTyped(*this, name, ParamType::Texture);
    if (!p) return "";
    expectCount(*p, 1, p->strings.size());
    return p->strings[0];
}

void ParamSet::reportUnused(const std::string& context) const {
    for (const Param& p : params)
        if (!p.used && !p.fromAttribute)
            warning(p.loc, "unused parameter \"" + p.typeName + " " + p.name + "\" in " + context);
}

}  // namespace ps
