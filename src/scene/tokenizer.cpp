#include "scene/tokenizer.h"

#include <zlib.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

namespace ps {

namespace {

constexpr size_t kMaxSceneBytes = size_t(4) << 30;  // 4 GiB of scene text

bool endsWith(const std::string& s, const char* suffix) {
    size_t n = std::strlen(suffix);
    return s.size() >= n && s.compare(s.size() - n, n, suffix) == 0;
}

std::string readGzip(const std::string& path) {
    gzFile f = gzopen(path.c_str(), "rb");
    if (!f) throw InputError(path + ": cannot open: " + std::strerror(errno));
    std::string out;
    char buf[1 << 16];
    int n;
    while ((n = gzread(f, buf, sizeof buf)) > 0) {
        out.append(buf, size_t(n));
        if (out.size() > kMaxSceneBytes) {
            gzclose(f);
            throw InputError(path + ": decompressed scene is larger than 4 GiB");
        }
    }
    int err = 0;
    const char* msg = gzerror(f, &err);
    bool bad = n < 0 || (err != Z_OK && err != Z_STREAM_END);
    std::string what = msg ? msg : "";
    gzclose(f);
    if (bad) throw InputError(path + ": corrupt gzip data (" + what + ")");
    return out;
}

}  // namespace

Tokenizer::Tokenizer(std::string text, std::string name) : text_(std::move(text)), name_(std::move(name)) {
    auto byte = [&](size_t i) { return (unsigned char)text_[i]; };
    if (text_.size() >= 2 && ((byte(0) == 0xFF && byte(1) == 0xFE) || (byte(0) == 0xFE && byte(1) == 0xFF)))
        throw InputError(name_ + ": UTF-16 files are not supported; convert the scene to UTF-8");
    if (text_.size() >= 3 && text_.compare(0, 3, "\xEF\xBB\xBF") == 0) pos_ = lineStart_ = 3;  // UTF-8 BOM
}

std::unique_ptr<Tokenizer> Tokenizer::fromFile(const std::string& path) {
    std::string text;
    if (endsWith(path, ".gz")) {
        text = readGzip(path);
    } else {
        std::ifstream in(path, std::ios::binary);
        if (!in) throw InputError(path + ": cannot open scene file: " + std::strerror(errno));
        std::ostringstream ss;
        ss << in.rdbuf();
        text = ss.str();
    }
    return std::unique_ptr<Tokenizer>(new Tokenizer(std::move(text), path));
}

std::unique_ptr<Tokenizer> Tokenizer::fromString(std::string text, std::string displayName) {
    return std::unique_ptr<Tokenizer>(new Tokenizer(std::move(text), std::move(displayName)));
}

std::optional<Token> Tokenizer::next() {
    const size_t n = text_.size();
    while (pos_ < n) {
        char c = text_[pos_];
        if (c == '\n') {
            ++pos_;
            ++line_;
            lineStart_ = pos_;
        } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
            ++pos_;
        } else if (c == '#') {
            while (pos_ < n && text_[pos_] != '\n') ++pos_;
        } else {
            break;
        }
    }
    if (pos_ >= n) return std::nullopt;
    Token t;
    t.line = line_;
    t.column = int(pos_ - lineStart_) + 1;
    size_t start = pos_;
    char c = text_[pos_];
    if (c == '[' || c == ']') {
        ++pos_;
    } else if (c == '"') {
        ++pos_;
        while (true) {
            if (pos_ >= n || text_[pos_] == '\n')
                throw InputError(loc(t), "unterminated string " + text_.substr(start, std::min<size_t>(pos_ - start, 40)));
            if (text_[pos_] == '\\') {
                pos_ += 2;
                continue;
            }
            if (text_[pos_] == '"') {
                ++pos_;
                break;
            }
            ++pos_;
        }
    } else {
        while (pos_ < n) {
            char d = text_[pos_];
            if (d == ' ' || d == '\n' || d == '\t' || d == '\r' || d == '\f' || d == '\v' || d == '"' || d == '[' ||
                d == ']' || d == '#')
                break;
            ++pos_;
        }
    }
    t.text = std::string_view(text_).substr(start, pos_ - start);
    return t;
}

std::string Tokenizer::dequote(const Token& t) const {
    std::string out;
    std::string_view s = t.text.substr(1, t.text.size() - 2);
    out.reserve(s.size());
    for (size_t i = 0; i < s.size(); ++i) {
        if (s[i] != '\\') {
            out += s[i];
            continue;
        }
        if (++i >= s.size()) break;
        switch (s[i]) {
            case 'b': out += '\b'; break;
            case 'f': out += '\f'; break;
            case 'n': out += '\n'; break;
            case 'r': out += '\r'; break;
            case 't': out += '\t'; break;
            case '\\': out += '\\'; break;
            case '\'': out += '\''; break;
            case '"': out += '"'; break;
            default:
                throw InputError(loc(t), std::string("unknown escape sequence \\") + s[i] + " in string");
        }
    }
    return out;
}

}  // namespace ps
