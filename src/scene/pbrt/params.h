// A directive's typed parameter list: "type name" value pairs (pbrt-v4 File
// Format, "Parameter lists"; its ParameterDictionary). Lookups check the type
// the directive expects and mark the parameter used, so that parameters no
// directive reads can be reported (an error, or a warning when lenient).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/math.h"
#include "scene/pbrt/tokenizer.h"

namespace pathlab::pbrt {

enum class ParamType {
    Integer,
    Float,
    Point2,
    Vector2,
    Point3,
    Vector3,
    Normal,
    Rgb,
    Spectrum,
    Blackbody,
    Bool,
    String,
    Texture
};
const char* paramTypeName(ParamType type);

// The value of a number token: InputError at the token unless it is a
// Number that reads as a finite double, all of it.
double parseNumber(const Token& t);

struct Param {
    ParamType type;
    std::string name;
    std::vector<double> numbers;       // integer, float, point*, vector*, normal, rgb, blackbody,
                                       // and spectrum given as (lambda, value) pairs
    std::vector<std::string> strings;  // string, texture, and spectrum given by name or file
    std::vector<bool> bools;
    SourceLocation where;  // of the "type name" string
    mutable bool used = false;
};

class ParamSet {
  public:
    // Parses "type name" (at `where`) with its values; InputError for an
    // unknown type, a malformed declaration, or values of the wrong kind/count.
    void add(const std::string& declaration, const SourceLocation& where,
             const std::vector<Token>& values);

    // Single values with defaults. InputError when the parameter exists with
    // another type or with more or fewer than one value.
    float getFloat(const std::string& name, float fallback) const;
    int getInt(const std::string& name, int fallback) const;
    bool getBool(const std::string& name, bool fallback) const;
    std::string getString(const std::string& name, const std::string& fallback) const;
    std::optional<Vec3f> getPoint3(const std::string& name) const;
    std::optional<Vec3f> getVector3(const std::string& name) const;

    // Arrays (empty when absent).
    std::vector<float> getFloats(const std::string& name) const;
    std::vector<int> getInts(const std::string& name) const;
    std::vector<Vec3f> getPoint3s(const std::string& name) const;
    std::vector<Vec3f> getNormals(const std::string& name) const;
    std::vector<Vec2f> getPoint2s(const std::string& name) const;

    // A parameter of any type (marked used), or null.
    const Param* find(const std::string& name) const;
    // Marks a parameter as read without using it (documented as ignored).
    void ignore(const std::string& name) const;
    // The parameters nothing read.
    std::vector<const Param*> unused() const;
    bool empty() const { return params_.empty(); }
    const std::vector<Param>& all() const { return params_; }

    // A copy whose values fall back to `defaults` (pbrt-v4's Attribute
    // directive): parameters of *this win.
    ParamSet withDefaults(const ParamSet& defaults) const;
    void merge(const ParamSet& other);  // other's parameters replace same-named ones
    // The parameters named prefix + x, as x (pbrt-v4's "conductor.eta" and
    // "interface.roughness" of coatedconductor); marks them used here.
    ParamSet withPrefix(const std::string& prefix) const;

  private:
    const Param* lookup(const std::string& name, ParamType type, size_t arity) const;
    std::vector<Param> params_;
};

}  // namespace pathlab::pbrt
