// The lexical layer of pbrt-v4's scene format (pbrt-v4 File Format, "Basic
// syntax"; its parser.cpp Tokenizer): whitespace-separated words, numbers,
// quoted strings with C escapes, '[' and ']', and '#' comments to the end of
// the line. Every token carries its file, line and column, so that every error
// the importer reports is one line "FILE:LINE:COL: problem".
#pragma once

#include <memory>
#include <string>
#include <string_view>

#include "core/error.h"

namespace pathlab::pbrt {

struct SourceLocation {
    std::shared_ptr<const std::string> file;  // shared by all tokens of a file
    int line = 1, column = 1;
    std::string str() const;  // "FILE:LINE:COL"
};

// An error at a place in a scene file: what() is "FILE:LINE:COL: message".
InputError errorAt(const SourceLocation& where, const std::string& message);

enum class TokenKind { Word, Number, String, OpenBracket, CloseBracket, End };

struct Token {
    TokenKind kind = TokenKind::End;
    std::string text;  // the word, the number as written, or the unescaped string
    SourceLocation where;
};

// Reads one file (or text in memory) token by token.
class Tokenizer {
  public:
    // Reads the whole file; InputError (naming `includedFrom` when given) if it
    // cannot be read.
    static std::unique_ptr<Tokenizer> fromFile(const std::string& path,
                                               const SourceLocation* includedFrom = nullptr);
    Tokenizer(std::string text, std::string fileName);

    // The next token; TokenKind::End at the end of the text. InputError on an
    // unterminated string, an unknown escape or a stray character.
    Token next();
    const std::string& fileName() const { return *file_; }

  private:
    char peek() const { return pos_ < text_.size() ? text_[pos_] : '\0'; }
    char advance();
    void skipSpaceAndComments();
    Token readString(SourceLocation start);

    std::string text_;
    std::shared_ptr<const std::string> file_;
    size_t pos_ = 0;
    int line_ = 1, column_ = 1;
};

}  // namespace pathlab::pbrt
