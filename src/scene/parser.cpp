#include "scene/parser.h"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <set>

#include "scene/tokenizer.h"
#include "util/path.h"

namespace ps {

namespace {

constexpr int kMaxIncludeDepth = 64;
constexpr size_t kMaxParamValues = size_t(1) << 28;

struct GraphicsState {
    Transform ctm;
    bool reverseOrientation = false;
    MaterialRef material{0, ""};
    int areaLight = -1;
    std::map<std::string, std::vector<Param>> attributes;  // "shape", "light", ... -> defaults
};

// One token of lookahead over a tokenizer.
class TokenStream {
public:
    explicit TokenStream(Tokenizer& t) : tok(t) {}
    std::optional<Token> peek() {
        if (!peeked) peeked = tok.next();
        return peeked;
    }
    std::optional<Token> next() {
        if (peeked) {
            auto t = peeked;
            peeked.reset();
            return t;
        }
        return tok.next();
    }
    SourceLoc loc(const Token& t) const { return tok.loc(t); }
    Tokenizer& tok;
    std::optional<Token> peeked;
};

bool isV3Material(const std::string& t) {
    static const std::set<std::string> v3 = {"matte", "plastic", "glass", "uber", "metal", "mirror", "substrate", "translucent"};
    return v3.count(t) > 0;
}

class SceneParser {
public:
    explicit SceneParser(SceneDescription& desc) : desc_(desc) {
        desc_.camera.type = "perspective";
        desc_.film.type = "rgb";
        desc_.sampler.type = "zsobol";
        desc_.integrator.type = "volpath";
        desc_.filter.type = "gaussian";
        for (SceneEntity* e : {static_cast<SceneEntity*>(&desc_.camera), &desc_.film, &desc_.sampler, &desc_.integrator, &desc_.filter})
            e->params.baseDirectory = desc_.baseDirectory;
        MaterialEntity def;
        def.type = "diffuse";
        def.loc = SourceLoc{"<default material>", 0, 0};
        desc_.materials.push_back(def);
    }

    void parseFile(const std::string& path, int depth, const SourceLoc* from) {
        if (depth > kMaxIncludeDepth)
            throw InputError(*from, "Include/Import nested more than " + std::to_string(kMaxIncludeDepth) + " deep (a cycle?)");
        std::unique_ptr<Tokenizer> tok;
        try {
            tok = Tokenizer::fromFile(path);
        } catch (const InputError& e) {
            if (from) throw InputError(*from, std::string("cannot read included file: ") + e.what());
            throw;
        }
        parse(*tok, depth);
    }

    void parse(Tokenizer& tokenizer, int depth) {
        TokenStream ts(tokenizer);
        while (auto t = ts.next()) directive(ts, *t, depth);
    }

    void finish() {
        if (!stack_.empty()) warning("scene ends with " + std::to_string(stack_.size()) + " unclosed AttributeBegin block(s)");
        if (instance_) throw InputError(instance_->loc, "ObjectBegin \"" + instance_->name + "\" has no matching ObjectEnd");
    }

private:
    // ---- token helpers ----
    [[noreturn]] void fail(TokenStream& ts, const Token& t, const std::string& msg) {
        throw InputError(ts.loc(t), msg + " (at '" + std::string(t.text.substr(0, 60)) + "')");
    }
    Token need(TokenStream& ts, const Token& after, const char* what) {
        auto t = ts.next();
        if (!t) throw InputError(ts.loc(after), std::string("unexpected end of file: expected ") + what);
        return *t;
    }
    double number(TokenStream& ts, const Token& t) {
        double v = 0;
        const char* b = t.text.data();
        const char* e = b + t.text.size();
        if (b != e && *b == '+') ++b;
        auto [p, ec] = std::from_chars(b, e, v);
        if (ec != std::errc() || p != e) fail(ts, t, "expected a number");
        if (!std::isfinite(v)) fail(ts, t, "numbers must be finite");
        return v;
    }
    std::string quoted(TokenStream& ts, const Token& after, const char* what) {
        Token t = need(ts, after, what);
        if (!t.isString()) fail(ts, t, std::string("expected a quoted string: ") + what);
        return ts.tok.dequote(t);
    }
    std::vector<double> bareNumbers(TokenStream& ts, const Token& dir, int n) {
        std::vector<double> v;
        for (int i = 0; i < n; ++i) {
            Token t = need(ts, dir, "a number");
            if (t.text == "[") fail(ts, t, std::string(dir.text) + " takes bare numbers, without brackets");
            v.push_back(number(ts, t));
        }
        return v;
    }
    std::vector<double> bracketNumbers(TokenStream& ts, const Token& dir, int n) {
        Token open = need(ts, dir, "'['");
        if (open.text != "[") fail(ts, open, std::string(dir.text) + " needs " + std::to_string(n) + " numbers in brackets");
        std::vector<double> v;
        while (true) {
            Token t = need(ts, dir, "']'");
            if (t.text == "]") break;
            v.push_back(number(ts, t));
            if (int(v.size()) > n) fail(ts, t, std::string(dir.text) + " takes exactly " + std::to_string(n) + " numbers");
        }
        if (int(v.size()) != n) fail(ts, open, std::string(dir.text) + " takes exactly " + std::to_string(n) + " numbers");
        return v;
    }

    ParamSet params(TokenStream& ts, const Token& dir) {
        ParamSet ps;
        ps.loc = ts.loc(dir);
        ps.baseDirectory = desc_.baseDirectory;
        while (true) {
            auto t = ts.peek();
            if (!t || !t->isString()) break;
            ts.next();
            ps.add(param(ts, *t));
        }
        return ps;
    }

    Param param(TokenStream& ts, const Token& declTok) {
        std::string decl = ts.tok.dequote(declTok);
        Param p;
        p.loc = ts.loc(declTok);
        size_t a = decl.find_first_not_of(" \t");
        size_t b = a == std::string::npos ? a : decl.find_first_of(" \t", a);
        size_t c = b == std::string::npos ? b : decl.find_first_not_of(" \t", b);
        size_t d = c == std::string::npos ? c : decl.find_first_of(" \t", c);
        if (c == std::string::npos || (d != std::string::npos && decl.find_first_not_of(" \t", d) != std::string::npos))
            fail(ts, declTok, "parameter declaration must be \"type name\"");
        p.typeName = decl.substr(a, b - a);
        p.name = decl.substr(c, d == std::string::npos ? std::string::npos : d - c);
        static const std::map<std::string, ParamType> types = {
            {"float", ParamType::Float},     {"integer", ParamType::Integer}, {"bool", ParamType::Bool},
            {"string", ParamType::String},   {"point2", ParamType::Point2},   {"vector2", ParamType::Vector2},
            {"point3", ParamType::Point3},   {"vector3", ParamType::Vector3}, {"normal", ParamType::Normal},
            {"rgb", ParamType::RGB},         {"blackbody", ParamType::Blackbody}, {"spectrum", ParamType::Spectrum},
            {"texture", ParamType::Texture},
        };
        auto it = types.find(p.typeName);
        if (it == types.end()) {
            if (p.typeName == "normal3" || p.typeName == "point" || p.typeName == "vector" || p.typeName == "color")
                fail(ts, declTok, "parameter type \"" + p.typeName + "\" is pbrt-v3 syntax; convert the file with `pbrt --upgrade`");
            fail(ts, declTok, "unknown parameter type \"" + p.typeName + "\"");
        }
        p.type = it->second;

        // Values: one token, or a bracketed list.
        std::vector<Token> values;
        Token first = need(ts, declTok, "a parameter value");
        if (first.text == "[") {
            while (true) {
                Token t = need(ts, first, "']'");
                if (t.text == "]") break;
                if (t.text == "[") fail(ts, t, "nested '[' in a parameter list");
                values.push_back(t);
                if (values.size() > kMaxParamValues) fail(ts, t, "parameter list is too long");
            }
        } else {
            values.push_back(first);
        }
        for (const Token& v : values) {
            switch (p.type) {
                case ParamType::Bool:
                    if (v.text == "true") p.bools.push_back(true);
                    else if (v.text == "false") p.bools.push_back(false);
                    else if (v.isString()) fail(ts, v, "bool values are bare true/false, not quoted (pbrt-v3 syntax)");
                    else fail(ts, v, "expected true or false");
                    break;
                case ParamType::String:
                case ParamType::Texture:
                    if (!v.isString()) fail(ts, v, "expected a quoted string for \"" + decl + "\"");
                    p.strings.push_back(ts.tok.dequote(v));
                    break;
                case ParamType::Spectrum:
                    if (v.isString()) p.strings.push_back(ts.tok.dequote(v));
                    else p.numbers.push_back(number(ts, v));
                    if (!p.strings.empty() && !p.numbers.empty()) fail(ts, v, "spectrum mixes names and numbers");
                    break;
                case ParamType::Integer: {
                    if (v.isString()) fail(ts, v, "expected an integer for \"" + decl + "\"");
                    std::string_view s = v.text;
                    if (s.find_first_of(".eE") != std::string_view::npos) fail(ts, v, "expected an integer, got a floating-point number");
                    double x = number(ts, v);
                    if (x < -2147483648.0 || x > 2147483647.0) fail(ts, v, "integer out of range");
                    p.numbers.push_back(x);
                    break;
                }
                default:
                    if (v.isString()) fail(ts, v, "expected a number for \"" + decl + "\"");
                    p.numbers.push_back(number(ts, v));
            }
        }
        return p;
    }

    // ---- state helpers ----
    void requireOptions(TokenStream& ts, const Token& t) {
        if (inWorld_) fail(ts, t, std::string(t.text) + " is only allowed before WorldBegin");
    }
    void requireWorld(TokenStream& ts, const Token& t) {
        if (!inWorld_) fail(ts, t, std::string(t.text) + " is only allowed after WorldBegin");
    }
    void applyAttributes(ParamSet& ps, const std::string& category) {
        auto it = gs_.attributes.find(category);
        if (it == gs_.attributes.end()) return;
        for (Param p : it->second) {
            p.fromAttribute = true;
            ps.addDefault(std::move(p));
        }
    }
    void setCtm(TokenStream& ts, const Token& t, const Matrix4& m) {
        auto tr = Transform::fromMatrix(m);
        if (!tr) fail(ts, t, "transform is not invertible");
        gs_.ctm = *tr;
    }
    void concat(TokenStream& ts, const Token& t, const Transform& tr) {
        Transform r = gs_.ctm * tr;
        if (!r.matrix().isFinite() || !r.inverseMatrix().isFinite()) fail(ts, t, "transform is not finite");
        gs_.ctm = r;
    }
    Matrix4 columnMajor(const std::vector<double>& v) {
        Matrix4 m;
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) m.m[j][i] = float(v[i * 4 + j]);
        return m;
    }
    std::string resolve(const std::string& f) const { return resolvePath(desc_.baseDirectory, f); }

    void directive(TokenStream& ts, const Token& t, int depth) {
        if (t.isString() || t.text == "[" || t.text == "]") fail(ts, t, "expected a directive");
        const std::string name(t.text);
        const SourceLoc loc = ts.loc(t);

        if (name == "Identity") {
            gs_.ctm = Transform();
        } else if (name == "Translate") {
            auto v = bareNumbers(ts, t, 3);
            concat(ts, t, Transform::translate(Vec3(float(v[0]), float(v[1]), float(v[2]))));
        } else if (name == "Scale") {
            auto v = bareNumbers(ts, t, 3);
            if (v[0] == 0 || v[1] == 0 || v[2] == 0) fail(ts, t, "Scale by zero makes the transform singular");
            concat(ts, t, Transform::scale(Vec3(float(v[0]), float(v[1]), float(v[2]))));
        } else if (name == "Rotate") {
            auto v = bareNumbers(ts, t, 4);
            if (v[1] == 0 && v[2] == 0 && v[3] == 0) fail(ts, t, "Rotate axis is zero");
            concat(ts, t, Transform::rotate(float(v[0]), Vec3(float(v[1]), float(v[2]), float(v[3]))));
        } else if (name == "LookAt") {
            auto v = bareNumbers(ts, t, 9);
            auto la = Transform::lookAt(Vec3(float(v[0]), float(v[1]), float(v[2])), Vec3(float(v[3]), float(v[4]), float(v[5])),
                                        Vec3(float(v[6]), float(v[7]), float(v[8])));
            if (!la) fail(ts, t, "LookAt: eye equals target, or up is parallel to the view direction");
            concat(ts, t, la->inverse());  // the CTM is camera-from-world
        } else if (name == "Transform") {
            setCtm(ts, t, columnMajor(bracketNumbers(ts, t, 16)));
        } else if (name == "ConcatTransform") {
            auto tr = Transform::fromMatrix(columnMajor(bracketNumbers(ts, t, 16)));
            if (!tr) fail(ts, t, "transform is not invertible");
            concat(ts, t, *tr);
        } else if (name == "CoordinateSystem") {
            namedCoordSys_[quoted(ts, t, "a coordinate system name")] = gs_.ctm;
        } else if (name == "CoordSysTransform") {
            std::string n = quoted(ts, t, "a coordinate system name");
            auto it = namedCoordSys_.find(n);
            if (it == namedCoordSys_.end()) warning(loc, "CoordSysTransform: unknown coordinate system \"" + n + "\"");
            else gs_.ctm = it->second;
        } else if (name == "ReverseOrientation") {
            gs_.reverseOrientation = !gs_.reverseOrientation;
        } else if (name == "Camera") {
            requireOptions(ts, t);
            desc_.camera.type = quoted(ts, t, "the camera type");
            desc_.camera.params = params(ts, t);
            desc_.camera.loc = loc;
            desc_.camera.worldFromCamera = gs_.ctm.inverse();
            desc_.cameraGiven = true;
            namedCoordSys_["camera"] = desc_.camera.worldFromCamera;
        } else if (name == "Film" || name == "Sampler" || name == "Integrator" || name == "PixelFilter" || name == "Accelerator") {
            requireOptions(ts, t);
            SceneEntity e;
            e.type = quoted(ts, t, "a type name");
            e.params = params(ts, t);
            e.loc = loc;
            if (name == "Film" && e.type == "image") fail(ts, t, "Film \"image\" is pbrt-v3 syntax; convert the file with `pbrt --upgrade`");
            if (name == "Film") desc_.film = e;
            else if (name == "Sampler") desc_.sampler = e;
            else if (name == "Integrator") desc_.integrator = e;
            else if (name == "PixelFilter") desc_.filter = e;
        } else if (name == "ColorSpace") {
            std::string cs = quoted(ts, t, "a colour space name");
            if (toLower(cs) != "srgb") warning(loc, "ColorSpace \"" + cs + "\" is not supported; RGB values are read as sRGB");
        } else if (name == "Option") {
            Token n = need(ts, t, "an option name");
            if (!n.isString()) fail(ts, n, "expected a quoted option name");
            std::string on = ts.tok.dequote(n);
            if (on.find(' ') != std::string::npos) fail(ts, n, "Option takes a bare name and value (the typed form is not accepted)");
            Token v = need(ts, n, "an option value");
            desc_.options[on] = v.isString() ? ts.tok.dequote(v) : std::string(v.text);
        } else if (name == "WorldBegin") {
            requireOptions(ts, t);
            inWorld_ = true;
            gs_.ctm = Transform();
            namedCoordSys_["world"] = gs_.ctm;
        } else if (name == "WorldEnd") {
            fail(ts, t, "WorldEnd is pbrt-v3 syntax (pbrt-v4 has none); remove it or convert with `pbrt --upgrade`");
        } else if (name == "AttributeBegin" || name == "TransformBegin") {
            if (name == "TransformBegin") warning(loc, "TransformBegin is deprecated; treated as AttributeBegin");
            stack_.push_back(gs_);
        } else if (name == "AttributeEnd" || name == "TransformEnd") {
            if (stack_.empty()) fail(ts, t, "unmatched " + name);
            gs_ = stack_.back();
            stack_.pop_back();
        } else if (name == "Attribute") {
            std::string cat = quoted(ts, t, "an attribute category");
            if (cat != "shape" && cat != "light" && cat != "material" && cat != "medium" && cat != "texture")
                fail(ts, t, "unknown Attribute category \"" + cat + "\"");
            ParamSet ps = params(ts, t);
            auto& list = gs_.attributes[cat];
            for (Param& p : ps.params) {
                auto it = std::find_if(list.begin(), list.end(), [&](const Param& q) { return q.name == p.name; });
                if (it != list.end()) *it = p;
                else list.push_back(p);
            }
        } else if (name == "Material") {
            requireWorld(ts, t);
            MaterialEntity m;
            m.type = quoted(ts, t, "a material type");
            if (isV3Material(m.type)) fail(ts, t, "material \"" + m.type + "\" is pbrt-v3 syntax; convert the file with `pbrt --upgrade`");
            m.params = params(ts, t);
            applyAttributes(m.params, "material");
            m.loc = loc;
            desc_.materials.push_back(std::move(m));
            gs_.material = MaterialRef{int(desc_.materials.size()) - 1, ""};
        } else if (name == "MakeNamedMaterial") {
            requireWorld(ts, t);
            MaterialEntity m;
            m.name = quoted(ts, t, "a material name");
            m.params = params(ts, t);
            applyAttributes(m.params, "material");
            m.loc = loc;
            const Param* type = m.params.find("type");
            if (!type || type->type != ParamType::String || type->strings.size() != 1)
                fail(ts, t, "MakeNamedMaterial \"" + m.name + "\" needs \"string type\"");
            m.type = type->strings[0];
            if (isV3Material(m.type)) fail(ts, t, "material \"" + m.type + "\" is pbrt-v3 syntax; convert the file with `pbrt --upgrade`");
            m.params.params.erase(std::remove_if(m.params.params.begin(), m.params.params.end(),
                                                 [](const Param& p) { return p.name == "type"; }),
                                  m.params.params.end());
            if (desc_.namedMaterials.count(m.name)) fail(ts, t, "named material \"" + m.name + "\" redefined");
            desc_.namedMaterials[m.name] = std::move(m);
        } else if (name == "NamedMaterial") {
            requireWorld(ts, t);
            gs_.material = MaterialRef{-1, quoted(ts, t, "a material name")};
        } else if (name == "Texture") {
            requireWorld(ts, t);
            TextureEntity e;
            e.name = quoted(ts, t, "a texture name");
            std::string kind = quoted(ts, t, "\"float\" or \"spectrum\"");
            if (kind == "color") fail(ts, t, "texture type \"color\" is pbrt-v3 syntax; use \"spectrum\"");
            if (kind != "float" && kind != "spectrum") fail(ts, t, "texture type must be \"float\" or \"spectrum\"");
            e.isFloat = kind == "float";
            e.type = quoted(ts, t, "a texture class");
            e.params = params(ts, t);
            applyAttributes(e.params, "texture");
            e.loc = loc;
            e.worldFromTexture = gs_.ctm;
            (e.isFloat ? desc_.floatTextures : desc_.spectrumTextures).push_back(std::move(e));
        } else if (name == "LightSource") {
            requireWorld(ts, t);
            LightEntity e;
            e.type = quoted(ts, t, "a light type");
            e.params = params(ts, t);
            applyAttributes(e.params, "light");
            e.loc = loc;
            e.worldFromLight = gs_.ctm;
            desc_.lights.push_back(std::move(e));
        } else if (name == "AreaLightSource") {
            requireWorld(ts, t);
            SceneEntity e;
            e.type = quoted(ts, t, "an area light type");
            e.params = params(ts, t);
            applyAttributes(e.params, "light");
            e.loc = loc;
            desc_.areaLights.push_back(std::move(e));
            gs_.areaLight = int(desc_.areaLights.size()) - 1;
        } else if (name == "Shape") {
            requireWorld(ts, t);
            ShapeEntity e;
            e.type = quoted(ts, t, "a shape type");
            e.params = params(ts, t);
            applyAttributes(e.params, "shape");
            e.loc = loc;
            e.worldFromObject = gs_.ctm;
            e.reverseOrientation = gs_.reverseOrientation;
            e.material = gs_.material;
            e.areaLight = gs_.areaLight;
            if (instance_) {
                if (e.areaLight >= 0) warning(loc, "area lights inside ObjectBegin are not supported; the shape does not emit");
                e.areaLight = -1;
                instance_->shapes.push_back(std::move(e));
            } else {
                desc_.shapes.push_back(std::move(e));
            }
        } else if (name == "ObjectBegin") {
            requireWorld(ts, t);
            std::string n = quoted(ts, t, "an object name");
            if (instance_) fail(ts, t, "ObjectBegin inside ObjectBegin \"" + instance_->name + "\"");
            if (desc_.instances.count(n)) fail(ts, t, "object \"" + n + "\" redefined");
            stack_.push_back(gs_);
            InstanceDefinition& def = desc_.instances[n];
            def.name = n;
            def.loc = loc;
            instance_ = &def;
            instanceDepth_ = stack_.size();
        } else if (name == "ObjectEnd") {
            requireWorld(ts, t);
            if (!instance_ || stack_.size() != instanceDepth_) fail(ts, t, "ObjectEnd without matching ObjectBegin");
            instance_ = nullptr;
            gs_ = stack_.back();
            stack_.pop_back();
        } else if (name == "ObjectInstance") {
            requireWorld(ts, t);
            std::string n = quoted(ts, t, "an object name");
            if (instance_) fail(ts, t, "ObjectInstance inside an ObjectBegin block");
            desc_.instanceUses.push_back(InstanceUse{n, gs_.ctm, loc});
        } else if (name == "Include") {
            std::string f = quoted(ts, t, "a file name");
            parseFile(resolve(f), depth + 1, &loc);
        } else if (name == "Import") {
            requireWorld(ts, t);
            std::string f = quoted(ts, t, "a file name");
            // Parsed against a copy of the graphics state: changes do not leak back.
            GraphicsState saved = gs_;
            auto savedStack = stack_;
            parseFile(resolve(f), depth + 1, &loc);
            gs_ = saved;
            stack_ = savedStack;
        } else if (name == "MakeNamedMedium") {
            std::string n = quoted(ts, t, "a medium name");
            params(ts, t);
            warning(loc, "participating media are not supported; medium \"" + n + "\" is ignored");
        } else if (name == "MediumInterface") {
            quoted(ts, t, "an interior medium name");
            if (auto nx = ts.peek(); nx && nx->isString()) ts.next();
            warning(loc, "participating media are not supported; MediumInterface is ignored");
        } else if (name == "TransformTimes") {
            requireOptions(ts, t);
            bareNumbers(ts, t, 2);
            warning(loc, "motion blur is not supported; TransformTimes is ignored");
        } else if (name == "ActiveTransform") {
            Token w = need(ts, t, "StartTime, EndTime or All");
            if (w.text != "StartTime" && w.text != "EndTime" && w.text != "All") fail(ts, w, "expected StartTime, EndTime or All");
            warning(loc, "motion blur is not supported; ActiveTransform is ignored");
        } else {
            fail(ts, t, "unknown directive \"" + name + "\"");
        }
    }

    SceneDescription& desc_;
    GraphicsState gs_;
    std::vector<GraphicsState> stack_;
    std::map<std::string, Transform> namedCoordSys_;
    bool inWorld_ = false;
    InstanceDefinition* instance_ = nullptr;
    size_t instanceDepth_ = 0;
};

}  // namespace

SceneDescription parseSceneFile(const std::string& path) {
    SceneDescription desc;
    desc.sceneFile = path;
    std::filesystem::path p(path);
    desc.baseDirectory = p.has_parent_path() ? p.parent_path().string() : ".";
    SceneParser parser(desc);
    parser.parseFile(path, 0, nullptr);
    parser.finish();
    return desc;
}

SceneDescription parseSceneString(const std::string& text, const std::string& baseDirectory, const std::string& displayName) {
    SceneDescription desc;
    desc.sceneFile = displayName;
    desc.baseDirectory = baseDirectory;
    SceneParser parser(desc);
    auto tok = Tokenizer::fromString(text, displayName);
    parser.parse(*tok, 0);
    parser.finish();
    return desc;
}

}  // namespace ps
