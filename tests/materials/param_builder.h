// Building ParamSets and texture entities in tests, as the parser would from
// `"float roughness" [0.1] "rgb reflectance" [...] "texture k" "name"` lists.
#pragma once
#include <string>
#include <vector>

#include "scene/scene_description.h"

namespace ps::test {

// Every set gets its own source line, so warnings (reported once per distinct message)
// can be counted per test.
inline SourceLoc freshLoc() {
    static int line = 0;
    return SourceLoc{"test.pbrt", ++line, 1};
}

class Params {
public:
    Params() { set_.loc = freshLoc(); }
    Params& f(const std::string& name, std::vector<double> v) { return add(ParamType::Float, "float", name, std::move(v)); }
    Params& f(const std::string& name, double v) { return f(name, std::vector<double>{v}); }
    Params& i(const std::string& name, int v) { return add(ParamType::Integer, "integer", name, {double(v)}); }
    Params& rgb(const std::string& name, double r, double g, double b) { return add(ParamType::RGB, "rgb", name, {r, g, b}); }
    Params& vec(const std::string& name, double x, double y, double z) { return add(ParamType::Vector3, "vector3", name, {x, y, z}); }
    Params& b(const std::string& name, bool v) {
        Param p = base(ParamType::Bool, "bool", name);
        p.bools = {v};
        set_.add(p);
        return *this;
    }
    Params& s(const std::string& name, std::vector<std::string> v) { return strings(ParamType::String, "string", name, std::move(v)); }
    Params& s(const std::string& name, const std::string& v) { return s(name, std::vector<std::string>{v}); }
    Params& tex(const std::string& name, const std::string& texture) { return strings(ParamType::Texture, "texture", name, {texture}); }
    Params& namedSpectrum(const std::string& name, const std::string& spectrum) {
        return strings(ParamType::Spectrum, "spectrum", name, {spectrum});
    }
    const ParamSet& set() const { return set_; }
    operator const ParamSet&() const { return set_; }

private:
    Param base(ParamType t, const std::string& typeName, const std::string& name) {
        Param p;
        p.type = t;
        p.typeName = typeName;
        p.name = name;
        p.loc = set_.loc;
        p.loc.column = int(set_.params.size()) + 2;
        return p;
    }
    Params& add(ParamType t, const std::string& typeName, const std::string& name, std::vector<double> v) {
        Param p = base(t, typeName, name);
        p.numbers = std::move(v);
        set_.add(p);
        return *this;
    }
    Params& strings(ParamType t, const std::string& typeName, const std::string& name, std::vector<std::string> v) {
        Param p = base(t, typeName, name);
        p.strings = std::move(v);
        set_.add(p);
        return *this;
    }
    ParamSet set_;
};

inline TextureEntity textureEntity(const std::string& name, const std::string& cls, bool isFloat, const Params& p) {
    TextureEntity e;
    e.name = name;
    e.type = cls;
    e.isFloat = isFloat;
    e.params = p.set();
    e.loc = p.set().loc;
    return e;
}

}  // namespace ps::test
