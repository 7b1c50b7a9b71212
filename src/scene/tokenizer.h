// Splits pbrt-v4 scene text into tokens, each with its file:line:column.
#pragma once
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include "util/error.h"

namespace ps {

struct Token {
    std::string_view text;  // raw text; quoted strings keep their quotes
    int line = 0, column = 0;
    bool isString() const { return !text.empty() && text.front() == '"'; }
};

class Tokenizer {
public:
    // Reads the file (gunzipping .gz files). Throws InputError if it cannot be read.
    static std::unique_ptr<Tokenizer> fromFile(const std::string& path);
    static std::unique_ptr<Tokenizer> fromString(std::string text, std::string displayName);

    std::optional<Token> next();
    const std::string& fileName() const { return name_; }
    SourceLoc loc(const Token& t) const { return SourceLoc{name_, t.line, t.column}; }
    // The contents of a quoted string token, escapes decoded.
    std::string dequote(const Token& t) const;

private:
    Tokenizer(std::string text, std::string name);
    std::string text_, name_;
    size_t pos_ = 0;
    int line_ = 1;
    size_t lineStart_ = 0;
};

}  // namespace ps
