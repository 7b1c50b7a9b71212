// Splits pbrt-v4 scene text into tokens, each with its file:line:column (PBRT-CONVENTIONS §8).
// The whole file is held in memory and tokens are views into it, so tokenising a large
// inline mesh costs one pass over the bytes and no allocation per token.
#pragma once
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include "util/error.h"

namespace ps {

struct Token {
    std::string_view text;               // raw text; quoted strings keep their quotes
    const std::string* file = nullptr;   // owned by the Tokenizer that produced the token
    int line = 0, column = 0;            // 1-based
    bool isString() const { return !text.empty() && text.front() == '"'; }
    bool is(std::string_view s) const { return text == s; }
    SourceLoc loc() const { return SourceLoc{file ? *file : std::string(), line, column}; }
};

class Tokenizer {
public:
    // Reads the whole file, gunzipping `.gz` files. Throws InputError if it cannot be read
    // or is UTF-16.
    static std::unique_ptr<Tokenizer> fromFile(const std::string& path);
    static std::unique_ptr<Tokenizer> fromString(std::string text, std::string displayName);

    // The next token, or nullopt at the end. Throws InputError for an unterminated string or
    // an unknown escape sequence, at the string's opening quote.
    std::optional<Token> next();

    const std::string& fileName() const { return name_; }
    SourceLoc loc(const Token& t) const { return SourceLoc{name_, t.line, t.column}; }
    // The contents of a quoted string token, escapes decoded (they were checked by next()).
    static std::string dequote(const Token& t);

private:
    Tokenizer(std::string text, std::string name);
    [[noreturn]] void fail(const Token& t, const std::string& msg) const;

    std::string text_, name_;
    size_t pos_ = 0;
    int line_ = 1;
    size_t lineStart_ = 0;
};

}  // namespace ps
