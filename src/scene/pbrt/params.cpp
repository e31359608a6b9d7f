#include "scene/pbrt/params.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace pathlab::pbrt {
namespace {

struct TypeName {
    const char* name;
    ParamType type;
};
// pbrt-v4's type names, with the synonyms its parser accepts.
constexpr TypeName kTypes[] = {
    {"integer", ParamType::Integer},   {"float", ParamType::Float},
    {"point2", ParamType::Point2},     {"vector2", ParamType::Vector2},
    {"point3", ParamType::Point3},     {"point", ParamType::Point3},
    {"vector3", ParamType::Vector3},   {"vector", ParamType::Vector3},
    {"normal", ParamType::Normal},     {"normal3", ParamType::Normal},
    {"rgb", ParamType::Rgb},           {"color", ParamType::Rgb},
    {"spectrum", ParamType::Spectrum}, {"blackbody", ParamType::Blackbody},
    {"bool", ParamType::Bool},         {"string", ParamType::String},
    {"texture", ParamType::Texture},
};

// How many numbers make one value of a numeric type.
size_t arityOf(ParamType t) {
    switch (t) {
        case ParamType::Point2:
        case ParamType::Vector2:
            return 2;
        case ParamType::Point3:
        case ParamType::Vector3:
        case ParamType::Normal:
        case ParamType::Rgb:
            return 3;
        default:
            return 1;
    }
}

bool isNumericType(ParamType t) {
    return t != ParamType::String && t != ParamType::Texture && t != ParamType::Bool &&
           t != ParamType::Spectrum;
}

}  // namespace

double parseNumber(const Token& t) {
    if (t.kind != TokenKind::Number)
        throw errorAt(t.where, "expected a number, got '" + t.text + "'");
    errno = 0;
    char* end = nullptr;
    const double v = std::strtod(t.text.c_str(), &end);
    if (end != t.text.c_str() + t.text.size() || errno == ERANGE || !std::isfinite(v))
        throw errorAt(t.where, "'" + t.text + "' is not a finite number");
    return v;
}

const char* paramTypeName(ParamType type) {
    for (const TypeName& t : kTypes)
        if (t.type == type) return t.name;
    return "?";
}

void ParamSet::add(const std::string& declaration, const SourceLocation& where,
                   const std::vector<Token>& values) {
    std::istringstream words(declaration);
    std::string typeName, name, extra;
    if (!(words >> typeName >> name) || (words >> extra))
        throw errorAt(where, "parameter declaration '" + declaration + "' must be \"type name\"");
    Param p{ParamType::Float, name, {}, {}, {}, where};
    bool known = false;
    for (const TypeName& t : kTypes)
        if (typeName == t.name) p.type = t.type, known = true;
    if (!known) throw errorAt(where, "unknown parameter type '" + typeName + "'");
    for (const Param& q : params_)
        if (q.name == name) throw errorAt(where, "parameter '" + name + "' given twice");
    if (values.empty()) throw errorAt(where, "parameter '" + name + "' has no values");
    for (const Token& v : values) {
        if (p.type == ParamType::Bool) {
            if (v.text != "true" && v.text != "false")
                throw errorAt(v.where, "bool parameter '" + name +
                                           "' must be true or false, got '" + v.text + "'");
            p.bools.push_back(v.text == "true");
        } else if (p.type == ParamType::String || p.type == ParamType::Texture) {
            if (v.kind != TokenKind::String)
                throw errorAt(v.where, std::string(paramTypeName(p.type)) + " parameter '" + name +
                                           "' needs quoted strings, got '" + v.text + "'");
            p.strings.push_back(v.text);
        } else if (p.type == ParamType::Spectrum && v.kind == TokenKind::String) {
            p.strings.push_back(v.text);  // a named spectrum or a file of samples
        } else {
            p.numbers.push_back(parseNumber(v));
            if (p.type == ParamType::Integer && p.numbers.back() != std::floor(p.numbers.back()))
                throw errorAt(v.where,
                              "integer parameter '" + name + "' has the value '" + v.text + "'");
        }
    }
    if (!p.strings.empty() && !p.numbers.empty())
        throw errorAt(where, "spectrum parameter '" + name + "' mixes numbers and names");
    if (isNumericType(p.type) && p.numbers.size() % arityOf(p.type) != 0)
        throw errorAt(where, std::string(paramTypeName(p.type)) + " parameter '" + name +
                                 "' needs a multiple of " + std::to_string(arityOf(p.type)) +
                                 " numbers, got " + std::to_string(p.numbers.size()));
    if (p.type == ParamType::Spectrum && !p.numbers.empty() && p.numbers.size() % 2 != 0)
        throw errorAt(where, "spectrum parameter '" + name +
                                 "' needs (wavelength, value) pairs, got an odd count");
    params_.push_back(std::move(p));
}

const Param* ParamSet::find(const std::string& name) const {
    for (const Param& p : params_)
        if (p.name == name) {
            p.used = true;
            return &p;
        }
    return nullptr;
}

void ParamSet::ignore(const std::string& name) const {
    find(name);
}

const Param* ParamSet::lookup(const std::string& name, ParamType type, size_t arity) const {
    const Param* p = find(name);
    if (!p) return nullptr;
    // pbrt-v4 reads point/vector/normal values interchangeably where it asks
    // for geometry; the names differ, the numbers do not.
    const bool sameKind = p->type == type ||
                          (arityOf(p->type) == 3 && arityOf(type) == 3 &&
                           p->type != ParamType::Rgb && type != ParamType::Rgb) ||
                          (arityOf(p->type) == 2 && arityOf(type) == 2);
    if (!sameKind)
        throw errorAt(p->where, "parameter '" + name + "' must be of type " + paramTypeName(type) +
                                    ", not " + paramTypeName(p->type));
    if (arity > 0) {
        const size_t count = type == ParamType::Bool     ? p->bools.size()
                             : type == ParamType::String ? p->strings.size()
                                                         : p->numbers.size() / arityOf(type);
        if (count != arity)
            throw errorAt(p->where, "parameter '" + name + "' must have exactly one value, got " +
                                        std::to_string(count));
    }
    return p;
}

float ParamSet::getFloat(const std::string& name, float fallback) const {
    const Param* p = lookup(name, ParamType::Float, 1);
    return p ? float(p->numbers[0]) : fallback;
}

int ParamSet::getInt(const std::string& name, int fallback) const {
    const Param* p = lookup(name, ParamType::Integer, 1);
    if (!p) return fallback;
    if (std::abs(p->numbers[0]) > 2147483647.0)
        throw errorAt(p->where, "integer parameter '" + name + "' is out of range");
    return int(p->numbers[0]);
}

bool ParamSet::getBool(const std::string& name, bool fallback) const {
    const Param* p = lookup(name, ParamType::Bool, 1);
    return p ? bool(p->bools[0]) : fallback;
}

std::string ParamSet::getString(const std::string& name, const std::string& fallback) const {
    const Param* p = lookup(name, ParamType::String, 1);
    return p ? p->strings[0] : fallback;
}

std::optional<Vec3f> ParamSet::getPoint3(const std::string& name) const {
    const Param* p = lookup(name, ParamType::Point3, 1);
    if (!p) return std::nullopt;
    return Vec3f(float(p->numbers[0]), float(p->numbers[1]), float(p->numbers[2]));
}

std::optional<Vec3f> ParamSet::getVector3(const std::string& name) const {
    const Param* p = lookup(name, ParamType::Vector3, 1);
    if (!p) return std::nullopt;
    return Vec3f(float(p->numbers[0]), float(p->numbers[1]), float(p->numbers[2]));
}

std::vector<float> ParamSet::getFloats(const std::string& name) const {
    const Param* p = lookup(name, ParamType::Float, 0);
    std::vector<float> out;
    if (p) out.assign(p->numbers.begin(), p->numbers.end());
    return out;
}

std::vector<int> ParamSet::getInts(const std::string& name) const {
    const Param* p = lookup(name, ParamType::Integer, 0);
    std::vector<int> out;
    if (!p) return out;
    out.reserve(p->numbers.size());
    for (double v : p->numbers) {
        if (std::abs(v) > 2147483647.0)
            throw errorAt(p->where, "integer parameter '" + name + "' has a value out of range");
        out.push_back(int(v));
    }
    return out;
}

namespace {
std::vector<Vec3f> triples(const Param* p) {
    std::vector<Vec3f> out;
    if (!p) return out;
    out.reserve(p->numbers.size() / 3);
    for (size_t i = 0; i + 2 < p->numbers.size(); i += 3)
        out.emplace_back(float(p->numbers[i]), float(p->numbers[i + 1]), float(p->numbers[i + 2]));
    return out;
}
}  // namespace

std::vector<Vec3f> ParamSet::getPoint3s(const std::string& name) const {
    return triples(lookup(name, ParamType::Point3, 0));
}

std::vector<Vec3f> ParamSet::getNormals(const std::string& name) const {
    return triples(lookup(name, ParamType::Normal, 0));
}

std::vector<Vec2f> ParamSet::getPoint2s(const std::string& name) const {
    const Param* p = find(name);
    std::vector<Vec2f> out;
    if (!p) return out;
    // pbrt-v4 also takes "float uv" [u0 v0 u1 v1 …] (older files).
    if (p->type != ParamType::Point2 && p->type != ParamType::Vector2 &&
        p->type != ParamType::Float)
        throw errorAt(p->where, "parameter '" + name + "' must be of type point2, not " +
                                    paramTypeName(p->type));
    if (p->numbers.size() % 2 != 0)
        throw errorAt(p->where, "parameter '" + name + "' needs pairs of numbers");
    for (size_t i = 0; i + 1 < p->numbers.size(); i += 2)
        out.push_back({float(p->numbers[i]), float(p->numbers[i + 1])});
    return out;
}

std::vector<const Param*> ParamSet::unused() const {
    std::vector<const Param*> out;
    for (const Param& p : params_)
        if (!p.used) out.push_back(&p);
    return out;
}

ParamSet ParamSet::withDefaults(const ParamSet& defaults) const {
    ParamSet out = *this;
    for (const Param& d : defaults.params_) {
        bool present = false;
        for (const Param& p : params_) present = present || p.name == d.name;
        if (present) continue;
        out.params_.push_back(d);
        // A default the directive does not read is no mistake of the file's.
        out.params_.back().used = true;
    }
    return out;
}

void ParamSet::merge(const ParamSet& other) {
    for (const Param& o : other.params_) {
        bool replaced = false;
        for (Param& p : params_)
            if (p.name == o.name) p = o, replaced = true;
        if (!replaced) params_.push_back(o);
    }
}

ParamSet ParamSet::withPrefix(const std::string& prefix) const {
    ParamSet out;
    for (const Param& p : params_) {
        if (p.name.size() <= prefix.size() || p.name.compare(0, prefix.size(), prefix) != 0)
            continue;
        p.used = true;
        out.params_.push_back(p);
        out.params_.back().name = p.name.substr(prefix.size());
        out.params_.back().used = false;
    }
    return out;
}

}  // namespace pathlab::pbrt
