// The token-level parser: directive syntax, parameter lists, numbers, Include and Import
// (PBRT-CONVENTIONS §8). What directives mean lives in directives.cpp.
#include "scene/parser.h"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <utility>

#include "scene/directives.h"
#include "scene/tokenizer.h"
#include "util/path.h"

namespace ps {

namespace {

// Resource limits: the parser must survive hostile input.
constexpr size_t kMaxOpenFiles = 64;                   // Include/Import nesting
constexpr size_t kMaxParamValues = size_t(1) << 28;    // values in one parameter list

std::string show(const Token& t) { return quoteForMessage(t.text); }

[[noreturn]] void fail(const Token& t, const std::string& msg) { throw InputError(t.loc(), msg); }

// ---- numbers ----

// pbrt-v4 accepts decimal, exponent and hex floats, but not inf/nan; the renderer works in
// single precision, so values beyond float range are refused too.
double parseFloat(const Token& t) {
    std::string_view s = t.text;
    bool negative = false;
    if (!s.empty() && (s[0] == '+' || s[0] == '-')) {
        negative = s[0] == '-';
        s.remove_prefix(1);
    }
    auto fmt = std::chars_format::general;
    if (s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) {
        s.remove_prefix(2);
        fmt = std::chars_format::hex;
    }
    double v = 0;
    if (s.empty() || s[0] == '+' || s[0] == '-') fail(t, "expected a number, got " + show(t));
    auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v, fmt);
    if (ec == std::errc::result_out_of_range) fail(t, "number out of range: " + show(t));
    if (ec != std::errc() || end != s.data() + s.size()) fail(t, "expected a number, got " + show(t));
    if (!std::isfinite(v)) fail(t, "numbers must be finite, got " + show(t));
    if (!std::isfinite(float(v))) fail(t, "number out of single-precision range: " + show(t));
    return negative ? -v : v;
}

// Integers are an optional sign and digits only: "2.0" is an error, as in pbrt-v4.
int parseInt(const Token& t) {
    std::string_view s = t.text;
    bool negative = false;
    if (!s.empty() && (s[0] == '+' || s[0] == '-')) {
        negative = s[0] == '-';
        s.remove_prefix(1);
    }
    if (s.empty()) fail(t, "expected an integer, got " + show(t));
    int64_t v = 0;
    for (char c : s) {
        if (c < '0' || c > '9') fail(t, "expected an integer, got " + show(t));
        v = v * 10 + (c - '0');
        if (v > int64_t(2147483647) + (negative ? 1 : 0)) fail(t, "integer out of 32-bit range: " + show(t));
    }
    return int(negative ? -v : v);
}

// ---- token stream over a stack of included files ----

struct ParseContext {
    explicit ParseContext(SceneDescription& d) : desc(d), builder(d) {}
    SceneDescription& desc;
    DescriptionBuilder builder;
    std::vector<std::string> openFiles;  // canonical paths being read, outermost first
};

std::string canonicalPath(const std::string& path) {
    std::error_code ec;
    auto p = std::filesystem::weakly_canonical(path, ec);
    return ec ? path : p.string();
}

// Tokens from the innermost open file; Include pushes a file so its text is read in place.
class TokenStream {
public:
    explicit TokenStream(ParseContext& ctx) : ctx_(ctx) {}
    ~TokenStream() {
        while (!files_.empty()) close();
    }

    // Opens `path` for reading in place; `from` is the Include/Import token for messages.
    void open(const std::string& path, const Token* from) {
        const std::string canon = canonicalPath(path);
        auto where = [&](const std::string& msg) -> InputError {
            return from ? InputError(from->loc(), std::string(from->text) + ": " + msg) : InputError(msg);
        };
        for (const std::string& f : ctx_.openFiles)
            if (f == canon) {
                std::string chain;
                for (const std::string& g : ctx_.openFiles) chain += g + " -> ";
                throw where("include cycle: " + chain + canon);
            }
        if (ctx_.openFiles.size() >= kMaxOpenFiles)
            throw where("Include/Import nested more than " + std::to_string(kMaxOpenFiles) + " files deep");
        std::unique_ptr<Tokenizer> tok;
        try {
            tok = Tokenizer::fromFile(path);
        } catch (const InputError& e) {
            if (!from) throw;
            throw where(std::string("cannot read the file: ") + e.what());
        }
        files_.push_back(std::move(tok));
        ctx_.openFiles.push_back(canon);
    }
    void openString(std::string text, std::string name) {
        files_.push_back(Tokenizer::fromString(std::move(text), std::move(name)));
        ctx_.openFiles.push_back("");  // no path: cannot be part of a cycle
    }

    std::optional<Token> next() {
        if (peeked_) return std::exchange(peeked_, std::nullopt);
        while (!files_.empty()) {
            if (auto t = files_.back()->next()) return t;
            close();
        }
        return std::nullopt;
    }
    const std::optional<Token>& peek() {
        if (!peeked_) peeked_ = next();
        return peeked_;
    }
    // The next token, which must exist: `after` names what it follows.
    Token need(const Token& after, const std::string& what) {
        auto t = next();
        if (!t) fail(after, "unexpected end of file after " + show(after) + ": expected " + what);
        return *t;
    }
    // Tokens point into the text of finished files until the current directive is done.
    void releaseFinished() { finished_.clear(); }

private:
    void close() {
        finished_.push_back(std::move(files_.back()));
        files_.pop_back();
        ctx_.openFiles.pop_back();
    }
    ParseContext& ctx_;
    std::vector<std::unique_ptr<Tokenizer>> files_, finished_;
    std::optional<Token> peeked_;
};

// ---- parameter lists ----

std::optional<ParamType> paramType(std::string_view s) {
    static const std::pair<std::string_view, ParamType> types[] = {
        {"float", ParamType::Float},     {"integer", ParamType::Integer},     {"bool", ParamType::Bool},
        {"string", ParamType::String},   {"point2", ParamType::Point2},       {"vector2", ParamType::Vector2},
        {"point3", ParamType::Point3},   {"vector3", ParamType::Vector3},     {"normal", ParamType::Normal},
        {"rgb", ParamType::RGB},         {"blackbody", ParamType::Blackbody}, {"spectrum", ParamType::Spectrum},
        {"texture", ParamType::Texture},
    };
    for (auto& [name, type] : types)
        if (name == s) return type;
    return std::nullopt;
}

void addValue(Param& p, const Token& v) {
    switch (p.type) {
        case ParamType::Bool:
            if (v.is("true") || v.is("false")) p.bools.push_back(v.is("true"));
            else if (v.is("\"true\"") || v.is("\"false\""))
                fail(v, "quoted bool " + show(v) + " is pbrt-v3 syntax: pbrt-v4 takes bare true/false; convert the file with `pbrt --upgrade`");
            else fail(v, "expected true or false for \"bool " + p.name + "\", got " + show(v));
            break;
        case ParamType::String:
        case ParamType::Texture:
            if (!v.isString()) fail(v, "expected a quoted string for \"" + p.typeName + " " + p.name + "\", got " + show(v));
            p.strings.push_back(Tokenizer::dequote(v));
            break;
        case ParamType::Spectrum:
            if (v.isString() ? !p.numbers.empty() : !p.strings.empty())
                fail(v, "\"spectrum " + p.name + "\" mixes names and numbers at " + show(v));
            if (v.isString()) p.strings.push_back(Tokenizer::dequote(v));
            else p.numbers.push_back(parseFloat(v));
            break;
        case ParamType::Integer:
            if (v.isString()) fail(v, "expected an integer for \"integer " + p.name + "\", got " + show(v));
            p.numbers.push_back(parseInt(v));
            break;
        default:
            if (v.isString()) fail(v, "expected a number for \"" + p.typeName + " " + p.name + "\", got " + show(v));
            p.numbers.push_back(parseFloat(v));
    }
}

Param parseParam(TokenStream& ts, const Token& decl) {
    // "type name": exactly two words.
    const std::string text = Tokenizer::dequote(decl);
    std::vector<std::string> words;
    for (size_t i = 0; i < text.size();) {
        size_t a = text.find_first_not_of(" \t", i);
        if (a == std::string::npos) break;
        size_t b = text.find_first_of(" \t", a);
        words.push_back(text.substr(a, b == std::string::npos ? std::string::npos : b - a));
        i = b == std::string::npos ? text.size() : b;
    }
    if (words.size() != 2) fail(decl, "expected a parameter declaration \"type name\", got " + show(decl));
    Param p;
    p.typeName = words[0];
    p.name = words[1];
    p.loc = decl.loc();
    auto type = paramType(p.typeName);
    if (!type) {
        if (p.typeName == "normal3" || p.typeName == "point" || p.typeName == "vector" || p.typeName == "color")
            fail(decl, "parameter type \"" + p.typeName + "\" in " + show(decl) + " is pbrt-v3 syntax; convert the file with `pbrt --upgrade`");
        fail(decl, "unknown parameter type \"" + p.typeName + "\" in " + show(decl));
    }
    p.type = *type;

    Token first = ts.need(decl, "a value for " + show(decl));
    if (first.is("[")) {
        while (true) {
            Token v = ts.need(first, "']' closing the values of " + show(decl));
            if (v.is("]")) break;
            if (v.is("[")) fail(v, "unexpected '[' inside the values of " + show(decl));
            if (p.numbers.size() + p.strings.size() + p.bools.size() >= kMaxParamValues)
                fail(v, "more than " + std::to_string(kMaxParamValues) + " values for " + show(decl));
            addValue(p, v);
        }
    } else if (first.is("]")) {
        fail(first, "unexpected ']' after " + show(decl));
    } else {
        addValue(p, first);
    }
    if (p.numbers.empty() && p.strings.empty() && p.bools.empty()) fail(decl, "no values given for " + show(decl));
    if (p.type == ParamType::Blackbody && p.numbers.size() == 2)
        fail(decl, show(decl) + " has two values: that is pbrt-v3's [kelvin scale] form; pbrt-v4 takes one temperature; "
                   "convert the file with `pbrt --upgrade`");
    return p;
}

// A parameter list runs until the first token that is not a quoted string.
ParamSet parseParams(ParseContext& ctx, TokenStream& ts, const Token& d) {
    ParamSet ps;
    ps.loc = d.loc();
    ps.baseDirectory = ctx.desc.baseDirectory;
    ps.colorSpace = ctx.builder.currentColorSpace();
    while (true) {
        const auto& t = ts.peek();
        if (!t || !t->isString()) break;
        Token decl = *ts.next();
        ps.add(parseParam(ts, decl));
    }
    return ps;
}

// ---- directive arguments ----

std::string quoted(TokenStream& ts, const Token& d, const std::string& what) {
    Token t = ts.need(d, what);
    if (!t.isString()) fail(t, std::string(d.text) + ": expected " + what + " (a quoted string), got " + show(t));
    return Tokenizer::dequote(t);
}

// LookAt, Translate, ...: bare numbers; brackets there are an error in pbrt-v4.
template <size_t N>
std::array<double, N> bareNumbers(TokenStream& ts, const Token& d) {
    std::array<double, N> v{};
    for (size_t i = 0; i < N; ++i) {
        Token t = ts.need(d, std::to_string(N) + " numbers");
        if (t.is("[") || t.is("]"))
            fail(t, std::string(d.text) + " takes " + std::to_string(N) + " bare numbers; brackets are not allowed (got " + show(t) + ")");
        v[i] = parseFloat(t);
    }
    return v;
}

// Transform and ConcatTransform: exactly 16 numbers in brackets.
std::array<double, 16> matrixNumbers(TokenStream& ts, const Token& d) {
    Token open = ts.need(d, "'[' and 16 numbers");
    if (!open.is("[")) fail(open, std::string(d.text) + " takes 16 numbers in brackets, got " + show(open));
    std::array<double, 16> v{};
    for (size_t i = 0; i < 16; ++i) {
        Token t = ts.need(open, "16 numbers");
        if (t.is("]")) fail(t, std::string(d.text) + " takes 16 numbers, got " + std::to_string(i) + " before " + show(t));
        v[i] = parseFloat(t);
    }
    Token close = ts.need(open, "']'");
    if (!close.is("]")) fail(close, std::string(d.text) + " takes exactly 16 numbers; expected ']', got " + show(close));
    return v;
}

Vec3 vec(const double* v) { return Vec3(float(v[0]), float(v[1]), float(v[2])); }

void parseStream(ParseContext& ctx, TokenStream& ts);

void includeFile(ParseContext& ctx, TokenStream& ts, const Token& d) {
    std::string f = quoted(ts, d, "a file name");
    if (f.empty()) fail(d, "Include: empty file name");
    // Relative to the main scene file's directory, not the including file's (§8).
    ts.open(resolvePath(ctx.desc.baseDirectory, f), &d);
}

void importFile(ParseContext& ctx, TokenStream& ts, const Token& d) {
    std::string f = quoted(ts, d, "a file name");
    if (f.empty()) fail(d, "Import: empty file name");
    auto saved = ctx.builder.beginImport(d);
    {
        TokenStream inner(ctx);
        inner.open(resolvePath(ctx.desc.baseDirectory, f), &d);
        parseStream(ctx, inner);
    }
    ctx.builder.endImport(d, std::move(saved));
}

void directive(ParseContext& ctx, TokenStream& ts, const Token& d) {
    DescriptionBuilder& b = ctx.builder;
    const std::string_view n = d.text;
    auto params = [&] { return parseParams(ctx, ts, d); };
    auto typeThenParams = [&](const char* what, auto method) {
        std::string type = quoted(ts, d, what);
        (b.*method)(d, type, params());
    };

    if (n == "Shape") typeThenParams("a shape type", &DescriptionBuilder::shape);
    else if (n == "AttributeBegin" || n == "TransformBegin") b.attributeBegin(d);
    else if (n == "AttributeEnd" || n == "TransformEnd") b.attributeEnd(d);
    else if (n == "Translate") {
        auto v = bareNumbers<3>(ts, d);
        b.translate(d, vec(v.data()));
    } else if (n == "Scale") {
        auto v = bareNumbers<3>(ts, d);
        b.scale(d, vec(v.data()));
    } else if (n == "Rotate") {
        auto v = bareNumbers<4>(ts, d);
        b.rotate(d, float(v[0]), vec(v.data() + 1));
    } else if (n == "LookAt") {
        auto v = bareNumbers<9>(ts, d);
        b.lookAt(d, vec(v.data()), vec(v.data() + 3), vec(v.data() + 6));
    } else if (n == "Transform") b.transform(d, matrixNumbers(ts, d).data());
    else if (n == "ConcatTransform") b.concatTransform(d, matrixNumbers(ts, d).data());
    else if (n == "Identity") b.identity(d);
    else if (n == "Material") typeThenParams("a material type", &DescriptionBuilder::material);
    else if (n == "MakeNamedMaterial") typeThenParams("a material name", &DescriptionBuilder::makeNamedMaterial);
    else if (n == "NamedMaterial") b.namedMaterial(d, quoted(ts, d, "a material name"));
    else if (n == "Texture") {
        std::string name = quoted(ts, d, "a texture name");
        std::string kind = quoted(ts, d, "\"float\" or \"spectrum\"");
        std::string cls = quoted(ts, d, "a texture class");
        b.texture(d, name, kind, cls, params());
    } else if (n == "LightSource") typeThenParams("a light type", &DescriptionBuilder::lightSource);
    else if (n == "AreaLightSource") typeThenParams("an area light type", &DescriptionBuilder::areaLightSource);
    else if (n == "ReverseOrientation") b.reverseOrientation(d);
    else if (n == "ObjectBegin") b.objectBegin(d, quoted(ts, d, "an object name"));
    else if (n == "ObjectEnd") b.objectEnd(d);
    else if (n == "ObjectInstance") b.objectInstance(d, quoted(ts, d, "an object name"));
    else if (n == "Attribute") typeThenParams("an attribute target", &DescriptionBuilder::attribute);
    else if (n == "CoordinateSystem") b.coordinateSystem(d, quoted(ts, d, "a coordinate system name"));
    else if (n == "CoordSysTransform") b.coordSysTransform(d, quoted(ts, d, "a coordinate system name"));
    else if (n == "Camera") typeThenParams("a camera type", &DescriptionBuilder::camera);
    else if (n == "Film") typeThenParams("a film type", &DescriptionBuilder::film);
    else if (n == "Sampler") typeThenParams("a sampler type", &DescriptionBuilder::sampler);
    else if (n == "Integrator") typeThenParams("an integrator type", &DescriptionBuilder::integrator);
    else if (n == "PixelFilter") typeThenParams("a filter type", &DescriptionBuilder::pixelFilter);
    else if (n == "Accelerator") typeThenParams("an accelerator type", &DescriptionBuilder::accelerator);
    else if (n == "WorldBegin") b.worldBegin(d);
    else if (n == "ColorSpace") b.colorSpace(d, quoted(ts, d, "a colour space name"));
    else if (n == "Option") {
        std::string name = quoted(ts, d, "an option name");
        Token value = ts.need(d, "an option value");
        b.option(d, name, value);
    } else if (n == "Include") includeFile(ctx, ts, d);
    else if (n == "Import") importFile(ctx, ts, d);
    else if (n == "MakeNamedMedium") typeThenParams("a medium name", &DescriptionBuilder::makeNamedMedium);
    else if (n == "MediumInterface") {
        std::string inside = quoted(ts, d, "a medium name"), outside = inside;
        if (const auto& t = ts.peek(); t && t->isString()) outside = Tokenizer::dequote(*ts.next());
        b.mediumInterface(d, inside, outside);
    } else if (n == "TransformTimes") {
        auto v = bareNumbers<2>(ts, d);
        b.transformTimes(d, float(v[0]), float(v[1]));
    } else if (n == "ActiveTransform") {
        Token w = ts.need(d, "StartTime, EndTime or All");
        if (!w.is("StartTime") && !w.is("EndTime") && !w.is("All"))
            fail(w, "ActiveTransform: expected StartTime, EndTime or All, got " + show(w));
        b.activeTransform(d, std::string(w.text));
    } else if (n == "WorldEnd") {
        fail(d, "WorldEnd is pbrt-v3 syntax (pbrt-v4 has no WorldEnd); remove it or convert the file with `pbrt --upgrade`");
    } else if (d.isString() || d.is("[") || d.is("]")) {
        fail(d, "expected a directive, got " + show(d));
    } else {
        fail(d, "unknown directive " + show(d));
    }
}

void parseStream(ParseContext& ctx, TokenStream& ts) {
    while (true) {
        ts.releaseFinished();
        auto t = ts.next();
        if (!t) break;
        directive(ctx, ts, *t);
    }
}

}  // namespace

SceneDescription parseSceneFile(const std::string& path) {
    SceneDescription desc;
    desc.sceneFile = path;
    std::filesystem::path p(path);
    desc.baseDirectory = p.has_parent_path() ? p.parent_path().string() : ".";
    ParseContext ctx(desc);
    {
        TokenStream ts(ctx);
        ts.open(path, nullptr);
        parseStream(ctx, ts);
    }
    ctx.builder.finish(path);
    return desc;
}

SceneDescription parseSceneString(const std::string& text, const std::string& baseDirectory, const std::string& displayName) {
    SceneDescription desc;
    desc.sceneFile = displayName;
    desc.baseDirectory = baseDirectory;
    ParseContext ctx(desc);
    {
        TokenStream ts(ctx);
        ts.openString(text, displayName);
        parseStream(ctx, ts);
    }
    ctx.builder.finish(displayName);
    return desc;
}

}  // namespace ps
