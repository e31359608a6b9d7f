// The grammar of pbrt-v4's scene format: directives, their positional
// arguments and parameter lists, Include/Import, and the graphics state's
// stack (pbrt-v4 File Format; its parser.cpp Parse and BasicSceneBuilder).
#include <filesystem>

#include "scene/pbrt/importer.h"
#include "scene/pbrt/parser_state.h"

namespace pathlab::pbrt {
namespace fs = std::filesystem;
namespace {

constexpr size_t kMaxIncludeDepth = 64;

class Parser {
  public:
    explicit Parser(ImportState& st) : st_(st) {}
    void pushSource(std::unique_ptr<Tokenizer> tok, std::string dir) {
        sources_.push_back({std::move(tok), std::move(dir), std::nullopt});
    }
    void run();

  private:
    struct Source {
        std::unique_ptr<Tokenizer> tok;
        std::string dir;  // of the file, for relative paths
        // Import: the importing file's graphics state, restored at the end
        // (pbrt-v4 parses an imported file with a copy of it; only named
        // things and shapes come back).
        std::optional<GraphicsState> restore;
    };
    struct Saved {
        GraphicsState gs;
        SourceLocation where;
        enum Kind { Attribute, Object } kind;
    };

    Token next();
    const Token& peek();
    std::string stringArg(const std::string& directive);
    double numberArg(const std::string& directive);
    std::vector<double> numbers(const std::string& directive, size_t count, bool bracketed);
    ParamSet params();
    void directive(const Token& t);
    void transformDirective(const std::string& name, const SourceLocation& where);
    void pushState(Saved::Kind kind, const SourceLocation& where);
    void popState(Saved::Kind kind, const Token& t);
    void include(const SourceLocation& where, bool import);
    void requireWorld(const Token& t, bool world);
    void typedDirective(const Token& t);
    void applyTransform(const Matrix4& m) {
        if (st_.gs.activeStart) st_.gs.ctm = st_.gs.ctm * m;
    }

    ImportState& st_;
    std::vector<Source> sources_;
    std::optional<Token> peeked_;
    std::vector<Saved> stack_;
    bool sawWorld_ = false;
};

// The next token of the current file: a directive never runs on into the
// file after it (run() moves on at a file's end).
Token Parser::next() {
    if (peeked_) {
        Token t = std::move(*peeked_);
        peeked_.reset();
        return t;
    }
    return sources_.back().tok->next();
}

const Token& Parser::peek() {
    if (!peeked_) peeked_ = next();
    return *peeked_;
}

std::string Parser::stringArg(const std::string& directive) {
    Token t = next();
    if (t.kind != TokenKind::String)
        throw errorAt(t.where, directive + " expects a quoted string" +
                                   (t.kind == TokenKind::End ? ", got the end of the file"
                                                             : ", got '" + t.text + "'"));
    return t.text;
}

double Parser::numberArg(const std::string& directive) {
    Token t = next();
    if (t.kind != TokenKind::Number)
        throw errorAt(t.where, directive + " expects a number" +
                                   (t.kind == TokenKind::End ? ", got the end of the file"
                                                             : ", got '" + t.text + "'"));
    return parseNumber(t);
}

std::vector<double> Parser::numbers(const std::string& directive, size_t count, bool bracketed) {
    const bool open = peek().kind == TokenKind::OpenBracket;
    if (bracketed && open) next();
    std::vector<double> v;
    for (size_t i = 0; i < count; ++i) v.push_back(numberArg(directive));
    if (bracketed && open) {
        Token close = next();
        if (close.kind != TokenKind::CloseBracket)
            throw errorAt(close.where,
                          directive + " expects ']' after " + std::to_string(count) + " numbers");
    }
    return v;
}

ParamSet Parser::params() {
    ParamSet ps;
    while (peek().kind == TokenKind::String) {
        const Token decl = next();
        std::vector<Token> values;
        const Token& v = peek();
        if (v.kind == TokenKind::OpenBracket) {
            const SourceLocation open = next().where;
            while (true) {
                Token t = next();
                if (t.kind == TokenKind::CloseBracket) break;
                if (t.kind == TokenKind::End || t.kind == TokenKind::OpenBracket)
                    throw errorAt(open, "unterminated '[' in the values of '" + decl.text + "'");
                values.push_back(std::move(t));
            }
        } else if (v.kind == TokenKind::Number || v.kind == TokenKind::String ||
                   (v.kind == TokenKind::Word && (v.text == "true" || v.text == "false"))) {
            values.push_back(next());
        } else {
            throw errorAt(decl.where, "parameter '" + decl.text + "' has no value");
        }
        ps.add(decl.text, decl.where, values);
    }
    return ps;
}

void Parser::requireWorld(const Token& t, bool world) {
    if (st_.inWorld != world)
        throw errorAt(t.where, t.text + (world ? " is only allowed after WorldBegin"
                                               : " is not allowed after WorldBegin"));
}

void Parser::pushState(Saved::Kind kind, const SourceLocation& where) {
    stack_.push_back({st_.gs, where, kind});
}

void Parser::popState(Saved::Kind kind, const Token& t) {
    if (stack_.empty() || stack_.back().kind != kind) {
        const char* opener = kind == Saved::Attribute ? "AttributeBegin" : "ObjectBegin";
        throw errorAt(t.where, "unbalanced " + t.text + ": no " + opener + " is open" +
                                   (stack_.empty() ? ""
                                                   : " (the innermost block opened at " +
                                                         stack_.back().where.str() + ")"));
    }
    st_.gs = std::move(stack_.back().gs);
    stack_.pop_back();
}

void Parser::include(const SourceLocation& where, bool import) {
    const std::string name = stringArg(import ? "Import" : "Include");
    if (sources_.size() >= kMaxIncludeDepth)
        throw errorAt(where, "Include nested more than " + std::to_string(kMaxIncludeDepth) +
                                 " deep (does a file include itself?)");
    // Relative to the including file; pbrt-v4 resolves against the main
    // file's directory, which we try second.
    fs::path path = fs::path(sources_.back().dir) / name;
    std::error_code ec;
    if (fs::path(name).is_relative() && !fs::exists(path, ec) &&
        fs::exists(fs::path(st_.mainDir) / name, ec))
        path = fs::path(st_.mainDir) / name;
    if (fs::path(name).is_absolute()) path = name;
    auto tok = Tokenizer::fromFile(path.string(), &where);
    pushSource(std::move(tok), path.parent_path().string());
    if (import) sources_.back().restore = st_.gs;
}

void Parser::transformDirective(const std::string& name, const SourceLocation& where) {
    if (name == "Identity") {
        if (st_.gs.activeStart) st_.gs.ctm = Matrix4();
    } else if (name == "Translate") {
        const auto v = numbers(name, 3, false);
        applyTransform(Matrix4::translate(v[0], v[1], v[2]));
    } else if (name == "Scale") {
        const auto v = numbers(name, 3, false);
        applyTransform(Matrix4::scale(v[0], v[1], v[2]));
    } else if (name == "Rotate") {
        const auto v = numbers(name, 4, false);
        applyTransform(Matrix4::rotate(v[0], v[1], v[2], v[3]));
    } else if (name == "LookAt") {
        const auto v = numbers(name, 9, false);
        const auto f = [&](int i) { return Vec3f(float(v[i]), float(v[i + 1]), float(v[i + 2])); };
        const auto m = Matrix4::lookAt(f(0), f(3), f(6));
        if (!m)
            throw errorAt(where,
                          "LookAt: the eye equals the look-at point, or 'up' is parallel "
                          "to the viewing direction");
        applyTransform(*m);
    } else if (name == "Transform" || name == "ConcatTransform") {
        const auto v = numbers(name, 16, true);
        const Matrix4 m = Matrix4::fromColumnMajor(v.data());
        if (name == "Transform") {
            if (st_.gs.activeStart) st_.gs.ctm = m;
        } else {
            applyTransform(m);
        }
    } else if (name == "CoordinateSystem") {
        st_.namedCoordinateSystems[stringArg(name)] = st_.gs.ctm;
    } else if (name == "CoordSysTransform") {
        const std::string cs = stringArg(name);
        const auto it = st_.namedCoordinateSystems.find(cs);
        if (it == st_.namedCoordinateSystems.end())
            throw errorAt(where, "CoordSysTransform: no coordinate system named '" + cs + "'");
        st_.gs.ctm = it->second;
    }
}

bool isTransformDirective(const std::string& n) {
    return n == "Identity" || n == "Translate" || n == "Scale" || n == "Rotate" || n == "LookAt" ||
           n == "Transform" || n == "ConcatTransform" || n == "CoordinateSystem" ||
           n == "CoordSysTransform";
}

}  // namespace

void Parser::run() {
    while (true) {
        const Token t = next();
        if (t.kind == TokenKind::End) {
            if (sources_.size() == 1) break;
            // The end of an included or imported file.
            if (sources_.back().restore) st_.gs = std::move(*sources_.back().restore);
            sources_.pop_back();
            continue;
        }
        if (t.kind != TokenKind::Word)
            throw errorAt(t.where, "expected a directive, got '" + t.text + "'");
        directive(t);
    }
    if (!stack_.empty())
        throw errorAt(stack_.back().where,
                      stack_.back().kind == Saved::Object
                          ? "ObjectBegin has no ObjectEnd"
                          : "this block is never closed (no AttributeEnd/TransformEnd)");
    if (!sawWorld_)
        throw InputError(sources_.front().tok->fileName() +
                         ": no WorldBegin: the file describes no scene");
}

void Parser::directive(const Token& t) {
    const std::string& d = t.text;
    if (isTransformDirective(d)) return transformDirective(d, t.where);
    if (d == "ReverseOrientation") {
        st_.gs.reverseOrientation = !st_.gs.reverseOrientation;
    } else if (d == "ActiveTransform") {
        const Token which = next();
        if (which.text == "StartTime" || which.text == "All") {
            st_.gs.activeStart = true;
        } else if (which.text == "EndTime") {
            st_.gs.activeStart = false;
            st_.note(t.where, "no motion blur: transforms at EndTime are ignored");
        } else {
            throw errorAt(which.where, "ActiveTransform expects StartTime, EndTime or All, got '" +
                                           which.text + "'");
        }
    } else if (d == "TransformTimes") {
        numbers(d, 2, false);
        st_.note(t.where, "no motion blur: TransformTimes ignored");
    } else if (d == "Include" || d == "Import") {
        include(t.where, d == "Import");
    } else if (d == "AttributeBegin") {
        pushState(Saved::Attribute, t.where);
    } else if (d == "AttributeEnd") {
        popState(Saved::Attribute, t);
    } else if (d == "TransformBegin") {
        // pbrt-v4 reads the deprecated TransformBegin/End as AttributeBegin/End.
        pushState(Saved::Attribute, t.where);
    } else if (d == "TransformEnd") {
        popState(Saved::Attribute, t);
    } else if (d == "Attribute") {
        const std::string target = stringArg(d);
        if (target != "shape" && target != "light" && target != "material" && target != "medium" &&
            target != "texture")
            throw errorAt(t.where,
                          "Attribute target must be shape, light, material, medium or "
                          "texture, got '" +
                              target + "'");
        st_.gs.attributes[target].merge(params());
    } else if (d == "Option") {
        stringArg(d);  // pbrt-v4: a name, then one value
        const Token value = next();
        if (value.kind == TokenKind::End || value.kind == TokenKind::OpenBracket ||
            value.kind == TokenKind::CloseBracket)
            throw errorAt(value.where, "Option expects a value after its name");
        st_.note(t.where, "Option ignored (pathlab has its own command-line options)");
    } else if (d == "ColorSpace") {
        const std::string cs = stringArg(d);
        if (cs != "srgb") st_.unsupported(t.where, "colour space '" + cs + "'", "sRGB primaries");
    } else if (d == "WorldBegin") {
        requireWorld(t, false);
        st_.inWorld = sawWorld_ = true;
        finishOptions(st_);
        st_.gs.ctm = Matrix4();
        st_.gs.activeStart = true;
        st_.namedCoordinateSystems["world"] = st_.gs.ctm;
    } else if (d == "WorldEnd") {
        st_.note(t.where, "WorldEnd (pbrt-v3) ignored");
    } else if (d == "ObjectBegin") {
        requireWorld(t, true);
        const std::string name = stringArg(d);
        if (st_.currentObject >= 0)
            throw errorAt(t.where, "ObjectBegin '" + name + "' inside another object");
        if (st_.objects.count(name))
            throw errorAt(t.where, "object '" + name + "' is defined twice");
        pushState(Saved::Object, t.where);
        st_.objects[name] = int(st_.result.scene.objects.size());
        st_.currentObject = int(st_.result.scene.objects.size());
        st_.result.scene.objects.push_back({name, {}, {}});
    } else if (d == "ObjectEnd") {
        popState(Saved::Object, t);
        st_.currentObject = -1;
    } else if (d == "ObjectInstance") {
        requireWorld(t, true);
        const std::string name = stringArg(d);
        const auto it = st_.objects.find(name);
        if (it == st_.objects.end())
            throw errorAt(t.where, "ObjectInstance: no object named '" + name + "'");
        if (st_.currentObject >= 0)
            throw errorAt(t.where, "ObjectInstance inside an object definition");
        if (!st_.gs.ctm.isAffine())
            throw errorAt(t.where, "ObjectInstance under a projective transform");
        st_.result.scene.instances.push_back({it->second, st_.gs.ctm.toAffine()});
    } else {
        typedDirective(t);
    }
}

// Directives of the form  Name "type" params.
void Parser::typedDirective(const Token& t) {
    const std::string& d = t.text;
    const auto optionsDirective = [&](auto fn) {
        requireWorld(t, false);
        const std::string type = stringArg(d);
        fn(st_, type, params(), t.where);
    };
    if (d == "Camera") {
        requireWorld(t, false);
        st_.cameraFromWorld = st_.gs.ctm;
        st_.cameraWhere = t.where;
        if (auto inv = st_.gs.ctm.inverse()) st_.namedCoordinateSystems["camera"] = *inv;
        optionsDirective(camera);
    } else if (d == "Film") {
        optionsDirective(film);
    } else if (d == "PixelFilter") {
        optionsDirective(pixelFilter);
    } else if (d == "Sampler") {
        optionsDirective(sampler);
    } else if (d == "Integrator") {
        optionsDirective(integrator);
    } else if (d == "Accelerator") {
        requireWorld(t, false);
        stringArg(d);
        params();
        st_.note(t.where, "Accelerator ignored: Embree builds its own BVH");
    } else if (d == "MakeNamedMedium") {
        stringArg(d);
        params();
        st_.unsupported(t.where, "participating media (MakeNamedMedium)", "no medium");
    } else if (d == "MediumInterface") {
        // One name (inside = outside) or two; an empty name is no medium.
        const std::string inside = stringArg(d);
        const std::string outside = peek().kind == TokenKind::String ? stringArg(d) : inside;
        if (!inside.empty() || !outside.empty())
            st_.unsupported(t.where, "participating media (MediumInterface)", "no medium");
    } else if (d == "Shape") {
        requireWorld(t, true);
        const std::string type = stringArg(d);
        const ParamSet ps = params();
        shape(st_, type, ps, t.where, sources_.back().dir);
    } else if (d == "Material" || d == "MakeNamedMaterial") {
        requireWorld(t, true);
        const std::string arg = stringArg(d);
        const ParamSet ps = params();
        if (d == "Material") {
            st_.gs.material = material(st_, arg, "", ps, t.where);
        } else {
            const Param* type = ps.find("type");
            if (!type || type->type != ParamType::String || type->strings.size() != 1)
                throw errorAt(t.where,
                              "MakeNamedMaterial '" + arg + "' needs a \"string type\" parameter");
            makeNamedMaterial(st_, arg, type->strings[0], ps, t.where);
        }
    } else if (d == "NamedMaterial") {
        requireWorld(t, true);
        st_.gs.material = namedMaterialRef(st_, stringArg(d), t.where, "NamedMaterial");
    } else if (d == "Texture") {
        requireWorld(t, true);
        const std::string name = stringArg(d), colorType = stringArg(d), cls = stringArg(d);
        texture(st_, name, colorType, cls, params(), t.where, sources_.back().dir);
    } else if (d == "LightSource") {
        requireWorld(t, true);
        const std::string type = stringArg(d);
        lightSource(st_, type, params(), t.where);
    } else if (d == "AreaLightSource") {
        requireWorld(t, true);
        const std::string type = stringArg(d);
        areaLightSource(st_, type, params(), t.where);
    } else {
        throw errorAt(t.where, "unknown directive '" + d + "'");
    }
}

namespace {
ImportResult runParser(std::unique_ptr<Tokenizer> tok, const std::string& dir,
                       const std::string& fileName, const ImportOptions& options) {
    ImportState st(options, dir);
    st.result.scene.name = fs::path(fileName).stem().string();
    Parser parser(st);
    parser.pushSource(std::move(tok), dir);
    parser.run();
    finishMaterials(st);
    return std::move(st.result);
}
}  // namespace

ImportResult importPbrtFile(const std::string& path, const ImportOptions& options) {
    auto tok = Tokenizer::fromFile(path);
    const std::string dir = fs::path(path).parent_path().string();
    return runParser(std::move(tok), dir.empty() ? "." : dir, path, options);
}

ImportResult importPbrtText(const std::string& text, const std::string& fileName,
                            const std::string& baseDir, const ImportOptions& options) {
    return runParser(std::make_unique<Tokenizer>(text, fileName), baseDir, fileName, options);
}

}  // namespace pathlab::pbrt
