#include "study/spec.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "core/error.h"
#include "sampling/registry.h"
#include "scene/light_selection.h"
#include "scene/loader.h"

namespace pathlab {
namespace {
namespace fs = std::filesystem;

constexpr int64_t kMaxSpp = int64_t(1) << 24;  // the renderer's limit

std::string joined(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
    return out;
}

std::vector<std::string> samplerNames() {
    std::vector<std::string> names;
    for (const SamplerInfo& info : samplerInfos()) names.push_back(info.name);
    return names;
}

// Turns toml++'s nodes into spec values; every complaint carries the source
// name, the line and the key, which is all a user needs to fix the file.
class SpecReader {
  public:
    SpecReader(std::string source, fs::path baseDir)
        : source_(std::move(source)), baseDir_(std::move(baseDir)) {}

    [[noreturn]] void fail(const toml::source_region& where, const std::string& key,
                           const std::string& problem) const {
        throw InputError(source_ + ":" + std::to_string(where.begin.line) + ": key '" + key + "' " +
                         problem);
    }
    [[noreturn]] void failType(const toml::node& n, const std::string& key,
                               const std::string& expected) const {
        std::ostringstream type;
        type << n.type();
        fail(n.source(), key, "must be " + expected + ", got " + type.str());
    }

    int64_t integer(const toml::node& n, const std::string& key, int64_t lo, int64_t hi) const {
        if (!n.is_integer()) failType(n, key, "an integer");
        const int64_t v = n.as_integer()->get();
        if (v < lo || v > hi)
            fail(n.source(), key,
                 "must be between " + std::to_string(lo) + " and " + std::to_string(hi) + ", got " +
                     std::to_string(v));
        return v;
    }
    double positiveNumber(const toml::node& n, const std::string& key) const {
        if (!n.is_number()) failType(n, key, "a number");
        const double v = n.value<double>().value_or(0.0);
        if (!(v > 0) || !std::isfinite(v)) fail(n.source(), key, "must be a positive number");
        return v;
    }
    std::string string(const toml::node& n, const std::string& key) const {
        if (!n.is_string()) failType(n, key, "a string");
        return n.as_string()->get();
    }
    bool boolean(const toml::node& n, const std::string& key) const {
        if (!n.is_boolean()) failType(n, key, "true or false");
        return n.as_boolean()->get();
    }
    const toml::array& array(const toml::node& n, const std::string& key) const {
        if (!n.is_array()) failType(n, key, "an array");
        const toml::array& a = *n.as_array();
        if (a.empty()) fail(n.source(), key, "must not be empty");
        return a;
    }
    // A non-empty list of distinct strings, each one of `allowed` when given.
    std::vector<std::string> names(const toml::node& n, const std::string& key,
                                   const std::vector<std::string>& allowed,
                                   const std::string& what) const {
        std::vector<std::string> out;
        const toml::array& a = array(n, key);
        for (size_t i = 0; i < a.size(); ++i) {
            const std::string item = key + "[" + std::to_string(i) + "]";
            std::string v = string(a[i], item);
            if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), v) == allowed.end())
                fail(a[i].source(), item,
                     "names an unknown " + what + " '" + v + "' (known: " + joined(allowed) + ")");
            if (std::find(out.begin(), out.end(), v) != out.end())
                fail(a[i].source(), item, "repeats '" + v + "'");
            out.push_back(std::move(v));
        }
        return out;
    }
    void onlyKeys(const toml::table& t, const std::string& prefix,
                  const std::vector<std::string>& allowed) const {
        for (auto&& [k, v] : t) {
            const std::string name(k.str());
            if (std::find(allowed.begin(), allowed.end(), name) == allowed.end())
                fail(k.source(), prefix + name,
                     "is not a study spec key (known: " + joined(allowed) + ")");
        }
    }
    const toml::node& required(const toml::table& t, const std::string& key) const {
        const toml::node* n = t.get(key);
        if (!n) throw InputError(source_ + ": key '" + key + "' is missing (it is required)");
        return *n;
    }

    std::vector<StudyScene> scenes(const toml::node& n) const;
    std::vector<int> sppList(const toml::node& n) const;
    Vec2i resolution(const toml::node& n) const;
    ReferenceSpec reference(const toml::node& n) const;
    std::vector<ExternalSpec> externals(const toml::node& n,
                                        const std::vector<StudyScene>& scenes) const;
    void difficulties(const toml::node& n, std::vector<StudyScene>& scenes) const;

  private:
    ExternalSpec external(const toml::node& n, const std::string& key,
                          const std::vector<StudyScene>& scenes) const;
    std::string path(const toml::node& n, const std::string& key) const;
    StudyScene scene(const toml::node& n, const std::string& key) const;

    std::string source_;
    fs::path baseDir_;
};

StudyScene SpecReader::scene(const toml::node& n, const std::string& key) const {
    const std::string v = string(n, key);
    const std::vector<std::string> builtins = builtinSceneNames();
    const std::string origin =
        source_ + ":" + std::to_string(n.source().begin.line) + ": key '" + key + "'";
    if (std::find(builtins.begin(), builtins.end(), v) != builtins.end()) return {v, v, origin};
    fs::path p(v);
    if (p.is_relative()) p = baseDir_ / p;
    std::error_code ec;
    if (!fs::is_regular_file(p, ec))
        fail(n.source(), key,
             "names '" + v + "': neither a built-in scene (" + joined(builtins) +
                 ") nor an existing scene file");
    const std::string ext = p.extension().string();
    if (ext != ".json" && ext != ".obj" && ext != ".pbrt")
        fail(n.source(), key, "names '" + v + "': a scene file must be .json, .obj or .pbrt");
    return {p.stem().string(), fs::absolute(p).lexically_normal().string(), origin};
}

std::vector<StudyScene> SpecReader::scenes(const toml::node& n) const {
    std::vector<StudyScene> out;
    const toml::array& a = array(n, "scenes");
    for (size_t i = 0; i < a.size(); ++i) {
        const std::string key = "scenes[" + std::to_string(i) + "]";
        StudyScene s = scene(a[i], key);
        for (const StudyScene& other : out)
            if (other.name == s.name)
                fail(a[i].source(), key, "gives a second scene named '" + s.name + "'");
        out.push_back(std::move(s));
    }
    return out;
}

// [difficulty]: scene name = "what makes it hard", for the scenes that say.
void SpecReader::difficulties(const toml::node& n, std::vector<StudyScene>& scenes) const {
    if (!n.is_table()) failType(n, "difficulty", "a table");
    for (auto&& [k, v] : *n.as_table()) {
        const std::string name(k.str()), key = "difficulty." + name;
        const auto scene = std::find_if(scenes.begin(), scenes.end(),
                                        [&](const StudyScene& s) { return s.name == name; });
        if (scene == scenes.end())
            fail(k.source(), key, "names no scene of the study ('" + name + "')");
        scene->difficulty = string(v, key);
        if (scene->difficulty.empty()) fail(v.source(), key, "must not be empty");
    }
}

std::vector<int> SpecReader::sppList(const toml::node& n) const {
    std::vector<int> out;
    const toml::array& a = array(n, "spp");
    for (size_t i = 0; i < a.size(); ++i) {
        const std::string key = "spp[" + std::to_string(i) + "]";
        const int v = int(integer(a[i], key, 1, kMaxSpp));
        if (std::find(out.begin(), out.end(), v) != out.end())
            fail(a[i].source(), key, "repeats " + std::to_string(v));
        out.push_back(v);
    }
    std::sort(out.begin(), out.end());
    return out;
}

Vec2i SpecReader::resolution(const toml::node& n) const {
    const toml::array& a = array(n, "resolution");
    if (a.size() != 2) fail(n.source(), "resolution", "must be [width, height]");
    return {int(integer(a[0], "resolution[0]", 1, 16384)),
            int(integer(a[1], "resolution[1]", 1, 16384))};
}

ReferenceSpec SpecReader::reference(const toml::node& n) const {
    if (!n.is_table()) failType(n, "reference", "a table");
    const toml::table& t = *n.as_table();
    onlyKeys(t, "reference.", {"spp", "sampler", "seed", "ranges"});
    ReferenceSpec r;
    if (const toml::node* v = t.get("spp")) r.spp = int(integer(*v, "reference.spp", 1, kMaxSpp));
    if (const toml::node* v = t.get("sampler")) {
        r.sampler = string(*v, "reference.sampler");
        const std::vector<std::string> known = samplerNames();
        if (std::find(known.begin(), known.end(), r.sampler) == known.end())
            fail(v->source(), "reference.sampler",
                 "names an unknown sampler '" + r.sampler + "' (known: " + joined(known) + ")");
    }
    if (const toml::node* v = t.get("seed"))
        r.seed = uint64_t(integer(*v, "reference.seed", 0, INT64_MAX));
    if (const toml::node* v = t.get("ranges")) {
        r.ranges = int(integer(*v, "reference.ranges", 1, kMaxReferenceRangeCount));
        if (r.ranges > r.spp)
            fail(v->source(), "reference.ranges",
                 "must be at most reference.spp (" + std::to_string(r.spp) +
                     "): every range holds samples");
    }
    return r;
}

std::string SpecReader::path(const toml::node& n, const std::string& key) const {
    fs::path p(string(n, key));
    if (p.empty()) fail(n.source(), key, "must not be empty");
    if (p.is_relative()) p = baseDir_ / p;
    return fs::absolute(p).lexically_normal().string();
}

// Only its keys and types here; study/external.h matches its files.
ExternalSpec SpecReader::external(const toml::node& n, const std::string& key,
                                  const std::vector<StudyScene>& scenes) const {
    if (!n.is_table()) failType(n, key, "a table");
    const toml::table& t = *n.as_table();
    onlyKeys(t, key + ".", {"name", "scene", "images", "times", "reference"});
    ExternalSpec e;
    const auto need = [&](const char* k) -> const toml::node& {
        const toml::node* v = t.get(k);
        if (!v) fail(n.source(), key + "." + k, "is missing (it is required)");
        return *v;
    };
    const toml::node& name = need("name");
    e.name = string(name, key + ".name");
    if (e.name.empty() || e.name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRS"
                                                   "TUVWXYZ0123456789_-.") != std::string::npos)
        fail(name.source(), key + ".name",
             "must be letters, digits, '-', '_' or '.', got '" + e.name + "'");
    const std::vector<std::string> own = samplerNames();
    if (std::find(own.begin(), own.end(), e.name) != own.end())
        fail(name.source(), key + ".name",
             "'" + e.name + "' is the name of a pathlab sampler: choose another");
    const toml::node& scene = need("scene");
    e.scene = string(scene, key + ".scene");
    e.images = path(need("images"), key + ".images");
    if (const toml::node* v = t.get("times")) e.times = path(*v, key + ".times");
    if (const toml::node* v = t.get("reference")) e.reference = path(*v, key + ".reference");
    const bool studyScene = std::any_of(scenes.begin(), scenes.end(),
                                        [&](const StudyScene& s) { return s.name == e.scene; });
    if (!studyScene && e.reference.empty())
        fail(scene.source(), key + ".scene",
             "names '" + e.scene +
                 "', which is not a scene of the study: give the study's scene or a 'reference'");
    e.origin = source_ + ":" + std::to_string(n.source().begin.line) + ": key '" + key + "'";
    return e;
}

std::vector<ExternalSpec> SpecReader::externals(const toml::node& n,
                                                const std::vector<StudyScene>& scenes) const {
    if (!n.is_array_of_tables()) failType(n, "external", "an array of tables ([[external]])");
    std::vector<ExternalSpec> out;
    const toml::array& a = *n.as_array();
    for (size_t i = 0; i < a.size(); ++i) {
        const std::string key = "external[" + std::to_string(i) + "]";
        ExternalSpec e = external(a[i], key, scenes);
        for (const ExternalSpec& other : out)
            if (other.name == e.name && other.scene == e.scene)
                fail(a[i].source(), key,
                     "repeats renderer '" + e.name + "' on scene '" + e.scene + "'");
        out.push_back(std::move(e));
    }
    return out;
}

StudySpec readSpec(const toml::table& t, const SpecReader& in) {
    in.onlyKeys(t, "",
                {"name", "scenes", "samplers", "spp", "seeds", "resolution", "max_depth",
                 "russian_roulette", "roulette_depth", "light_sampler", "spectral", "wavelengths",
                 "metrics", "time_budget_seconds", "reference", "external", "difficulty"});
    StudySpec s;
    if (const toml::node* v = t.get("name")) {
        s.name = in.string(*v, "name");
        if (s.name.empty()) in.fail(v->source(), "name", "must not be empty");
    }
    s.scenes = in.scenes(in.required(t, "scenes"));
    if (const toml::node* v = t.get("difficulty")) in.difficulties(*v, s.scenes);
    s.samplers = in.names(in.required(t, "samplers"), "samplers", samplerNames(), "sampler");
    s.spp = in.sppList(in.required(t, "spp"));
    if (const toml::node* v = t.get("seeds")) s.seeds = int(in.integer(*v, "seeds", 1, 10000));
    if (const toml::node* v = t.get("resolution")) s.resolution = in.resolution(*v);
    if (const toml::node* v = t.get("max_depth"))
        s.maxDepth = int(in.integer(*v, "max_depth", 0, 1024));
    if (const toml::node* v = t.get("russian_roulette"))
        s.russianRoulette = in.boolean(*v, "russian_roulette");
    if (const toml::node* v = t.get("roulette_depth"))
        s.rouletteDepth = int(in.integer(*v, "roulette_depth", 0, 1024));
    if (const toml::node* v = t.get("light_sampler")) {
        s.lightSampler = in.string(*v, "light_sampler");
        if (!lightSelectionNamed(s.lightSampler))
            in.fail(v->source(), "light_sampler",
                    std::string("must be one of ") + lightSelectionNames() + ", got '" +
                        s.lightSampler + "'");
    }
    if (const toml::node* v = t.get("spectral")) s.spectral = in.boolean(*v, "spectral");
    if (const toml::node* v = t.get("wavelengths")) {
        const std::string name = in.string(*v, "wavelengths");
        if (name != "visible" && name != "hero")
            in.fail(v->source(), "wavelengths",
                    "must be \"visible\" or \"hero\", got '" + name + "'");
        s.wavelengths = spectral::parseWavelengthSampling(name, "wavelengths");
        if (s.wavelengths != spectral::WavelengthSampling::Visible && !s.spectral)
            in.fail(v->source(), "wavelengths", "\"" + name + "\" needs spectral = true");
    }
    if (const toml::node* v = t.get("metrics"))
        s.metrics = in.names(*v, "metrics", knownStudyMetrics(), "metric");
    if (const toml::node* v = t.get("time_budget_seconds"))
        s.timeBudgetSeconds = in.positiveNumber(*v, "time_budget_seconds");
    if (const toml::node* v = t.get("reference")) {
        s.reference = in.reference(*v);
        const toml::node* seed = v->as_table()->get("seed");
        if (seed && s.reference.seed < uint64_t(s.seeds))
            in.fail(seed->source(), "reference.seed",
                    "must differ from the cells' seeds 0…" + std::to_string(s.seeds - 1));
    }
    if (const toml::node* v = t.get("external")) s.externals = in.externals(*v, s.scenes);
    return s;
}

// A TOML basic string: JSON's escapes are TOML's, but TOML also forbids a raw
// DEL (U+007F), which JSON leaves as it is.
std::string quoted(const std::string& s) {
    std::string out = nlohmann::json(s).dump();
    for (size_t p = out.find('\x7f'); p != std::string::npos; p = out.find('\x7f', p))
        out.replace(p, 1, "\\u007F");
    return out;
}

template <typename T, typename F>
std::string tomlArray(const std::vector<T>& items, F format) {
    std::string out = "[";
    for (size_t i = 0; i < items.size(); ++i) {
        if (i) out += ", ";
        out += format(items[i]);
    }
    return out + "]";
}

}  // namespace

bool StudySpec::wants(const std::string& metric) const {
    return metric == "mse" || std::find(metrics.begin(), metrics.end(), metric) != metrics.end();
}

const std::vector<std::string>& knownStudyMetrics() {
    static const std::vector<std::string> names{"mse", "rmse", "relmse", "psnr", "flip"};
    return names;
}

StudySpec parseStudySpec(const std::string& text, const std::string& sourceName,
                         const std::string& baseDir) {
    toml::table table;
    try {
        table = toml::parse(text, sourceName);
    } catch (const toml::parse_error& e) {
        const auto& where = e.source().begin;
        throw InputError(sourceName + ":" + std::to_string(where.line) + ":" +
                         std::to_string(where.column) +
                         ": not valid TOML: " + std::string(e.description()));
    }
    return readSpec(table, SpecReader(sourceName, baseDir));
}

StudySpec loadStudySpec(const std::string& path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec))
        throw InputError("study spec '" + path + "' does not exist or is not a file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError("cannot read study spec '" + path + "'");
    std::stringstream text;
    text << in.rdbuf();
    const fs::path base = fs::absolute(fs::path(path)).parent_path();
    return parseStudySpec(text.str(), path, base.string());
}

std::string studySpecToToml(const StudySpec& s) {
    const auto str = [](const std::string& v) { return quoted(v); };
    const auto num = [](int v) { return std::to_string(v); };
    std::vector<std::string> sources;
    for (const StudyScene& scene : s.scenes) sources.push_back(scene.source);
    std::ostringstream out;
    out << "# The resolved study spec (docs/study-spec.toml explains every key).\n"
        << "name = " << quoted(s.name) << "\n"
        << "scenes = " << tomlArray(sources, str) << "\n"
        << "samplers = " << tomlArray(s.samplers, str) << "\n"
        << "spp = " << tomlArray(s.spp, num) << "\n"
        << "seeds = " << s.seeds << "\n"
        << "resolution = [" << s.resolution.x << ", " << s.resolution.y << "]\n"
        << "max_depth = " << s.maxDepth << "\n"
        << "russian_roulette = " << (s.russianRoulette ? "true" : "false") << "\n"
        << "roulette_depth = " << s.rouletteDepth << "\n";
    if (!s.lightSampler.empty()) out << "light_sampler = " << quoted(s.lightSampler) << "\n";
    if (s.spectral) out << "spectral = true\n";
    if (s.wavelengths != spectral::WavelengthSampling::Visible)
        out << "wavelengths = " << quoted(spectral::wavelengthSamplingName(s.wavelengths)) << "\n";
    out << "metrics = " << tomlArray(s.metrics, str) << "\n";
    if (s.timeBudgetSeconds)
        out << "time_budget_seconds = " << nlohmann::json(*s.timeBudgetSeconds).dump() << "\n";
    out << "\n[reference]\n"
        << "spp = " << s.reference.spp << "\n"
        << "sampler = " << quoted(s.reference.sampler) << "\n"
        << "seed = " << s.reference.seed << "\n";
    if (s.reference.ranges) out << "ranges = " << s.reference.ranges << "\n";
    if (std::any_of(s.scenes.begin(), s.scenes.end(),
                    [](const StudyScene& scene) { return !scene.difficulty.empty(); })) {
        out << "\n[difficulty]\n";
        for (const StudyScene& scene : s.scenes)
            if (!scene.difficulty.empty())
                out << quoted(scene.name) << " = " << quoted(scene.difficulty) << "\n";
    }
    for (const ExternalSpec& e : s.externals) {
        out << "\n[[external]]\n"
            << "name = " << quoted(e.name) << "\n"
            << "scene = " << quoted(e.scene) << "\n"
            << "images = " << quoted(e.images) << "\n";
        if (!e.times.empty()) out << "times = " << quoted(e.times) << "\n";
        if (!e.reference.empty()) out << "reference = " << quoted(e.reference) << "\n";
    }
    return out.str();
}

std::string firstSpecDifference(const StudySpec& a, const StudySpec& b) {
    const auto sources = [](const StudySpec& s) {
        std::vector<std::string> v;
        for (const StudyScene& scene : s.scenes) v.push_back(scene.source);
        return v;
    };
    if (a.name != b.name) return "name";
    if (sources(a) != sources(b)) return "scenes";
    if (a.samplers != b.samplers) return "samplers";
    if (a.spp != b.spp) return "spp";
    if (a.seeds != b.seeds) return "seeds";
    if (a.resolution.x != b.resolution.x || a.resolution.y != b.resolution.y) return "resolution";
    if (a.maxDepth != b.maxDepth) return "max_depth";
    if (a.russianRoulette != b.russianRoulette) return "russian_roulette";
    if (a.rouletteDepth != b.rouletteDepth) return "roulette_depth";
    if (a.lightSampler != b.lightSampler) return "light_sampler";
    if (a.spectral != b.spectral) return "spectral";
    if (a.wavelengths != b.wavelengths) return "wavelengths";
    if (a.metrics != b.metrics) return "metrics";
    if (a.timeBudgetSeconds != b.timeBudgetSeconds) return "time_budget_seconds";
    if (a.reference.spp != b.reference.spp) return "reference.spp";
    if (a.reference.sampler != b.reference.sampler) return "reference.sampler";
    if (a.reference.seed != b.reference.seed) return "reference.seed";
    if (a.reference.ranges != b.reference.ranges) return "reference.ranges";
    // [difficulty] may differ: it only labels scenes for the report. So may
    // [[external]] tables: a resumed study measures the renders they name now
    // beside its own cells, which they do not change.
    return "";
}

}  // namespace pathlab
