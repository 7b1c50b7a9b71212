#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <filesystem>
#include <fstream>

#include "scene/tokenizer.h"

using namespace ps;
namespace fs = std::filesystem;

namespace {

std::vector<Token> all(Tokenizer& t) {
    std::vector<Token> out;
    while (auto x = t.next()) out.push_back(*x);
    return out;
}

std::string errorOf(const std::string& text) {
    try {
        auto t = Tokenizer::fromString(text, "t.pbrt");
        all(*t);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

fs::path tempDir() {
    fs::path d = fs::temp_directory_path() / ("pathspace-tok-" + std::to_string(getpid()));
    fs::create_directories(d);
    return d;
}

}  // namespace

TEST(Tokenizer, TokensCarryFileLineAndColumn) {
    auto t = Tokenizer::fromString("Shape \"sphere\" # comment [ ignored\n  [ 1.5 \"a\\\"b\" ]", "f.pbrt");
    auto toks = all(*t);
    ASSERT_EQ(toks.size(), 6u);
    EXPECT_EQ(toks[0].text, "Shape");
    EXPECT_EQ(toks[0].line, 1);
    EXPECT_EQ(toks[0].column, 1);
    EXPECT_EQ(toks[1].text, "\"sphere\"");
    EXPECT_TRUE(toks[1].isString());
    EXPECT_EQ(toks[1].column, 7);
    EXPECT_EQ(toks[2].text, "[");
    EXPECT_EQ(toks[2].line, 2);
    EXPECT_EQ(toks[2].column, 3);
    EXPECT_EQ(toks[3].text, "1.5");
    EXPECT_EQ(toks[3].column, 5);
    EXPECT_EQ(Tokenizer::dequote(toks[4]), "a\"b");
    EXPECT_EQ(toks[5].text, "]");
    EXPECT_EQ(toks[5].loc().str(), "f.pbrt:2:16");
    EXPECT_EQ(t->loc(toks[3]).str(), "f.pbrt:2:5");
}

TEST(Tokenizer, BracketsAndQuotesSplitWords) {
    auto t = Tokenizer::fromString("[1 2]\"x\"[\"y\"]a#b", "f");
    std::vector<std::string> texts;
    for (const Token& k : all(*t)) texts.emplace_back(k.text);
    // '#' starts a comment only at the start of a token, as in pbrt-v4.
    EXPECT_EQ(texts, (std::vector<std::string>{"[", "1", "2", "]", "\"x\"", "[", "\"y\"", "]", "a#b"}));
}

TEST(Tokenizer, CommentsAndLineEndings) {
    auto t = Tokenizer::fromString("# only a comment\r\n\r\n  WorldBegin\t# trailing\r\nShape", "f");
    auto toks = all(*t);
    ASSERT_EQ(toks.size(), 2u);
    EXPECT_EQ(toks[0].line, 3);
    EXPECT_EQ(toks[0].column, 3);
    EXPECT_EQ(toks[1].line, 4);
    EXPECT_EQ(toks[1].column, 1);
    EXPECT_TRUE(all(*Tokenizer::fromString("# no newline at the end", "f")).empty());
    EXPECT_TRUE(all(*Tokenizer::fromString("", "f")).empty());
}

TEST(Tokenizer, EscapesDecode) {
    auto t = Tokenizer::fromString(R"("\b\f\n\r\t\\\'\"x")", "f");
    auto toks = all(*t);
    ASSERT_EQ(toks.size(), 1u);
    EXPECT_EQ(Tokenizer::dequote(toks[0]), std::string("\b\f\n\r\t\\'\"x"));
}

TEST(Tokenizer, ErrorsNameTheLocationAndText) {
    std::string e = errorOf("Shape \"sphere\n");
    EXPECT_NE(e.find("t.pbrt:1:7: error: unterminated string"), std::string::npos) << e;
    EXPECT_NE(e.find("\"sphere"), std::string::npos) << e;
    e = errorOf("\n  \"abc");
    EXPECT_NE(e.find("t.pbrt:2:3:"), std::string::npos) << e;
    e = errorOf("x \"a\\qb\"");
    EXPECT_NE(e.find("t.pbrt:1:3:"), std::string::npos) << e;
    EXPECT_NE(e.find("\\q"), std::string::npos) << e;
    e = errorOf("\"ends with backslash\\\nnext\"");
    EXPECT_NE(e.find("t.pbrt:1:1:"), std::string::npos) << e;
}

TEST(Tokenizer, RejectsUtf16AndSkipsUtf8Bom) {
    std::string utf16 = "\xFF\xFE" + std::string("S\0h\0", 4);
    std::string e = errorOf(utf16);
    EXPECT_NE(e.find("UTF-16"), std::string::npos) << e;
    EXPECT_NE(errorOf("\xFE\xFF\0S").find("UTF-16"), std::string::npos);
    auto t = Tokenizer::fromString("\xEF\xBB\xBFWorldBegin", "f");
    auto toks = all(*t);
    ASSERT_EQ(toks.size(), 1u);
    EXPECT_EQ(toks[0].text, "WorldBegin");
    EXPECT_EQ(toks[0].column, 1);
}

TEST(Tokenizer, ReadsPlainAndGzippedFiles) {
    fs::path dir = tempDir();
    std::ofstream(dir / "plain.pbrt") << "LookAt 0 0 0\n";
    auto t = Tokenizer::fromFile((dir / "plain.pbrt").string());
    EXPECT_EQ(all(*t).size(), 4u);
    EXPECT_EQ(t->fileName(), (dir / "plain.pbrt").string());

    const std::string text = "WorldBegin\n  Shape \"sphere\"\n";
    for (const char* name : {"scene.pbrt.gz", "gzip-without-extension.pbrt"}) {
        std::string path = (dir / name).string();
        gzFile g = gzopen(path.c_str(), "wb");
        ASSERT_NE(g, nullptr);
        gzwrite(g, text.data(), unsigned(text.size()));
        gzclose(g);
        auto z = Tokenizer::fromFile(path);
        auto toks = all(*z);
        ASSERT_EQ(toks.size(), 3u) << name;
        EXPECT_EQ(toks[1].text, "Shape");
        EXPECT_EQ(toks[1].loc().str(), path + ":2:3");
    }
    // A truncated gzip stream is an input error, not garbage.
    {
        std::ifstream in(dir / "scene.pbrt.gz", std::ios::binary);
        std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        std::ofstream(dir / "cut.pbrt.gz", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    }
    EXPECT_THROW(Tokenizer::fromFile((dir / "cut.pbrt.gz").string()), InputError);
    try {
        Tokenizer::fromFile((dir / "missing.pbrt").string());
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("missing.pbrt"), std::string::npos);
    }
    EXPECT_THROW(Tokenizer::fromFile(dir.string()), InputError);  // a directory
    fs::remove_all(dir);
}
