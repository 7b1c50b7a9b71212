#include "scene/tokenizer.h"
#include "util/input_files.h"

#include <zlib.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace ps {

namespace {

// Decompressed .gz scenes larger than this are refused: a small hostile file could
// otherwise expand without bound.
constexpr size_t kMaxGzipBytes = size_t(4) << 30;

bool hasGzipExtension(const std::string& path) {
    return path.size() >= 3 && path.compare(path.size() - 3, 3, ".gz") == 0;
}

std::string readGzip(const std::string& path) {
    gzFile f = gzopen(path.c_str(), "rb");
    if (!f) throw InputError(path + ": cannot open: " + std::strerror(errno));
    gzbuffer(f, 1 << 17);
    std::string out;
    std::string buf(size_t(1) << 17, '\0');
    int n;
    while ((n = gzread(f, buf.data(), unsigned(buf.size()))) > 0) {
        out.append(buf.data(), size_t(n));
        if (out.size() > kMaxGzipBytes) {
            gzclose(f);
            throw InputError(path + ": decompressed scene is larger than 4 GiB");
        }
    }
    int err = Z_OK;
    const char* msg = gzerror(f, &err);
    std::string what = msg ? msg : "";
    gzclose(f);
    if (n < 0 || (err != Z_OK && err != Z_STREAM_END)) throw InputError(path + ": corrupt gzip data (" + what + ")");
    return out;
}

// Only regular files: a device such as /dev/zero would never end.
void requireRegularFile(const std::string& path) {
    std::error_code ec;
    auto st = std::filesystem::status(path, ec);
    if (ec || !std::filesystem::exists(st)) throw InputError(path + ": cannot open: no such file");
    if (std::filesystem::is_directory(st)) throw InputError(path + ": is a directory, not a scene file");
    if (!std::filesystem::is_regular_file(st)) throw InputError(path + ": not a regular file");
}

std::string readPlain(const std::string& path) {
    FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) throw InputError(path + ": cannot open: " + std::strerror(errno));
    std::string out;
    char buf[1 << 16];
    size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) out.append(buf, n);
    bool bad = std::ferror(f);
    std::fclose(f);
    if (bad) throw InputError(path + ": read error");
    return out;
}

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

bool isEscapable(char c) {
    return c == 'b' || c == 'f' || c == 'n' || c == 'r' || c == 't' || c == '\\' || c == '\'' || c == '"';
}

}  // namespace

Tokenizer::Tokenizer(std::string text, std::string name) : text_(std::move(text)), name_(std::move(name)) {
    auto byte = [&](size_t i) { return (unsigned char)text_[i]; };
    if (text_.size() >= 2 && ((byte(0) == 0xFF && byte(1) == 0xFE) || (byte(0) == 0xFE && byte(1) == 0xFF)))
        throw InputError(SourceLoc{name_, 1, 1}, "file is encoded as UTF-16, which pbrt-v4 does not read; convert it to UTF-8");
    if (text_.size() >= 3 && text_.compare(0, 3, "\xEF\xBB\xBF") == 0) pos_ = lineStart_ = 3;  // UTF-8 BOM
}

std::unique_ptr<Tokenizer> Tokenizer::fromFile(const std::string& path) {
    // Files are also recognised by the gzip magic number, whatever their name.
    requireRegularFile(path);
    noteInputFile(path);
    std::string text = hasGzipExtension(path) ? readGzip(path) : readPlain(path);
    if (!hasGzipExtension(path) && text.size() >= 2 && (unsigned char)text[0] == 0x1F && (unsigned char)text[1] == 0x8B)
        text = readGzip(path);
    return std::unique_ptr<Tokenizer>(new Tokenizer(std::move(text), path));
}

std::unique_ptr<Tokenizer> Tokenizer::fromString(std::string text, std::string displayName) {
    return std::unique_ptr<Tokenizer>(new Tokenizer(std::move(text), std::move(displayName)));
}

void Tokenizer::fail(const Token& t, const std::string& msg) const { throw InputError(loc(t), msg); }

std::optional<Token> Tokenizer::next() {
    const size_t n = text_.size();
    const char* s = text_.data();
    // Skip whitespace and comments.
    while (pos_ < n) {
        char c = s[pos_];
        if (c == '\n') {
            ++pos_;
            ++line_;
            lineStart_ = pos_;
        } else if (isSpace(c)) {
            ++pos_;
        } else if (c == '#') {
            const void* nl = std::memchr(s + pos_, '\n', n - pos_);
            pos_ = nl ? size_t(static_cast<const char*>(nl) - s) : n;
        } else {
            break;
        }
    }
    if (pos_ >= n) return std::nullopt;

    Token t;
    t.file = &name_;
    t.line = line_;
    t.column = int(pos_ - lineStart_) + 1;
    const size_t start = pos_;
    const char c = s[pos_];
    if (c == '[' || c == ']') {
        ++pos_;
    } else if (c == '"') {
        ++pos_;
        while (true) {
            if (pos_ >= n || s[pos_] == '\n') {
                t.text = std::string_view(s + start, std::min<size_t>(pos_ - start, 60));
                fail(t, "unterminated string " + std::string(t.text) + " (strings cannot span lines)");
            }
            if (s[pos_] == '\\') {
                if (pos_ + 1 >= n || s[pos_ + 1] == '\n') {
                    t.text = std::string_view(s + start, std::min<size_t>(pos_ + 1 - start, 60));
                    fail(t, "unterminated string " + std::string(t.text) + " (ends with a '\\')");
                }
                if (!isEscapable(s[pos_ + 1])) {
                    t.text = std::string_view(s + start, std::min<size_t>(pos_ + 2 - start, 60));
                    fail(t, std::string("unknown escape sequence '\\") + s[pos_ + 1] + "' in string " + std::string(t.text));
                }
                pos_ += 2;
                continue;
            }
            if (s[pos_++] == '"') break;
        }
    } else {
        // A bare word or number runs to whitespace, a quote or a bracket (as in pbrt-v4, a
        // '#' inside a word does not start a comment).
        while (pos_ < n) {
            char d = s[pos_];
            if (d == '\n' || isSpace(d) || d == '"' || d == '[' || d == ']') break;
            ++pos_;
        }
    }
    t.text = std::string_view(s + start, pos_ - start);
    return t;
}

std::string Tokenizer::dequote(const Token& t) {
    std::string_view s = t.text;
    if (s.size() >= 2 && s.front() == '"' && s.back() == '"') s = s.substr(1, s.size() - 2);
    std::string out;
    out.reserve(s.size());
    for (size_t i = 0; i < s.size(); ++i) {
        if (s[i] != '\\' || i + 1 >= s.size()) {
            out += s[i];
            continue;
        }
        switch (s[++i]) {
            case 'b': out += '\b'; break;
            case 'f': out += '\f'; break;
            case 'n': out += '\n'; break;
            case 'r': out += '\r'; break;
            case 't': out += '\t'; break;
            default: out += s[i]; break;  // \\ \' \" (others were rejected by next())
        }
    }
    return out;
}

}  // namespace ps
