#include "scene/pbrt/tokenizer.h"

#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace pathlab::pbrt {

std::string SourceLocation::str() const {
    return (file ? *file : std::string("<text>")) + ":" + std::to_string(line) + ":" +
           std::to_string(column);
}

InputError errorAt(const SourceLocation& where, const std::string& message) {
    return InputError(where.str() + ": " + message);
}

std::unique_ptr<Tokenizer> Tokenizer::fromFile(const std::string& path,
                                               const SourceLocation* includedFrom) {
    const auto fail = [&](const std::string& why) {
        return includedFrom ? errorAt(*includedFrom, why) : InputError(why);
    };
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw fail("file '" + path + "' does not exist");
    if (!std::filesystem::is_regular_file(path, ec))
        throw fail("'" + path + "' is not a regular file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw fail("cannot read '" + path + "'");
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) throw fail("cannot read '" + path + "'");
    return std::make_unique<Tokenizer>(text.str(), path);
}

Tokenizer::Tokenizer(std::string text, std::string fileName)
    : text_(std::move(text)), file_(std::make_shared<const std::string>(std::move(fileName))) {}

char Tokenizer::advance() {
    const char c = text_[pos_++];
    if (c == '\n') {
        ++line_;
        column_ = 1;
    } else {
        ++column_;
    }
    return c;
}

void Tokenizer::skipSpaceAndComments() {
    while (pos_ < text_.size()) {
        const char c = peek();
        if (c == '#') {
            while (pos_ < text_.size() && peek() != '\n') advance();
        } else if (std::isspace(static_cast<unsigned char>(c))) {
            advance();
        } else {
            return;
        }
    }
}

Token Tokenizer::readString(SourceLocation start) {
    advance();  // the opening quote
    Token t{TokenKind::String, {}, start};
    while (true) {
        if (pos_ >= text_.size() || peek() == '\n') throw errorAt(start, "unterminated string");
        const char c = advance();
        if (c == '"') return t;
        if (c != '\\') {
            t.text += c;
            continue;
        }
        if (pos_ >= text_.size()) throw errorAt(start, "unterminated string");
        const SourceLocation escape{file_, line_, column_ - 1};
        switch (const char e = advance()) {
            case 'b':
                t.text += '\b';
                break;
            case 'f':
                t.text += '\f';
                break;
            case 'n':
                t.text += '\n';
                break;
            case 'r':
                t.text += '\r';
                break;
            case 't':
                t.text += '\t';
                break;
            case '\\':
                t.text += '\\';
                break;
            case '\'':
                t.text += '\'';
                break;
            case '"':
                t.text += '"';
                break;
            default:
                throw errorAt(escape,
                              std::string("unknown escape sequence '\\") + e + "' in string");
        }
    }
}

Token Tokenizer::next() {
    skipSpaceAndComments();
    const SourceLocation start{file_, line_, column_};
    if (pos_ >= text_.size()) return {TokenKind::End, {}, start};
    const char c = peek();
    if (c == '"') return readString(start);
    if (c == '[' || c == ']') {
        advance();
        return {c == '[' ? TokenKind::OpenBracket : TokenKind::CloseBracket, std::string(1, c),
                start};
    }
    // A word or a number runs to the next space, bracket, quote or comment.
    Token t{TokenKind::Word, {}, start};
    while (pos_ < text_.size()) {
        const char d = peek();
        if (std::isspace(static_cast<unsigned char>(d)) || d == '[' || d == ']' || d == '"' ||
            d == '#')
            break;
        if (!std::isprint(static_cast<unsigned char>(d)))
            throw errorAt({file_, line_, column_},
                          "unexpected character (byte " +
                              std::to_string(static_cast<unsigned char>(d)) + ")");
        t.text += advance();
    }
    const char first = t.text[0];
    if (std::isdigit(static_cast<unsigned char>(first)) || first == '-' || first == '+' ||
        first == '.')
        t.kind = TokenKind::Number;
    return t;
}

}  // namespace pathlab::pbrt
