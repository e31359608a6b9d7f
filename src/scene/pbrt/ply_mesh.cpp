// A strict PLY reader: the header, then the body as a stream of values in the
// header's order (the PLY format, Turk 1994), ASCII or binary of either byte
// order, decoded one at a time by type (ply_stream.h). The vertex and face
// elements fill the mesh directly: the file is read once, through a 1 MiB
// buffer, and nothing the size of the mesh is built besides the mesh itself.
#include "scene/pbrt/ply_mesh.h"

#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <vector>

#include "core/error.h"
#include "scene/pbrt/ply_stream.h"

namespace pathlab::pbrt {
namespace {
namespace fs = std::filesystem;
using namespace ply;

// Where a vertex property's value goes (pbrt-v4's names), or a face's index list.
enum Slot : int { kSkip = -1, kX, kY, kZ, kNx, kNy, kNz, kU, kV, kSlots, kIndices = kSlots };

struct Property {
    std::string name;
    Type type = Type::Float32;  // the value type; a list's item type
    bool list = false;
    Type countType = Type::UInt8;
    int slot = kSkip;
};

struct Element {
    std::string name;
    uint64_t count = 0;
    std::vector<Property> props;
    Property* find(std::string_view name) {
        for (Property& p : props)
            if (p.name == name) return &p;
        return nullptr;
    }
};

enum class Format { Ascii, BinaryLittleEndian, BinaryBigEndian };

class PlyReader {
  public:
    explicit PlyReader(std::string path) : path_(std::move(path)) {}
    Mesh read();

  private:
    [[noreturn]] void fail(const std::string& what) const {
        throw InputError("PLY file '" + path_ + "': " + what);
    }
    void open();
    bool nextLine(std::string& line);
    void parseHeader();
    void checkHeader();
    template <typename In>
    void readBody(In in);
    template <typename In>
    void readVertices(In& in, const Element& e);
    template <typename In>
    void readFaces(In& in, const Element& e);
    template <typename In>
    void skipInstance(In& in, const Element& e);
    template <typename In>
    void skipList(In& in, const Property& p);

    struct Closer {
        void operator()(gzFile f) const { gzclose(f); }
    };
    std::string path_;
    std::unique_ptr<gzFile_s, Closer> file_;
    std::unique_ptr<Source> source_;
    uint64_t fileSize_ = 0, bodySize_ = 0;
    Format format_ = Format::Ascii;
    std::vector<Element> elements_;
    Element* vertex_ = nullptr;
    Element* face_ = nullptr;
    bool hasNormals_ = false, hasUvs_ = false;
    Mesh mesh_;
};

void PlyReader::open() {
    std::error_code ec;
    if (!fs::is_regular_file(path_, ec)) fail("does not exist or is not a file");
    fileSize_ = fs::file_size(path_, ec);
    file_.reset(gzopen(path_.c_str(), "rb"));
    if (!file_ || ec) fail("cannot be read");
    if (fileSize_ == 0) fail("is empty");
    gzbuffer(file_.get(), 1 << 17);
    // A gzip file's body is at most deflate's largest ratio (1032:1) times
    // its size: the bound below on what the header may declare.
    if (!gzdirect(file_.get())) fileSize_ *= 1032;
    source_ = std::make_unique<Source>(file_.get());
}

// The next header line without its line end; false at the end of the file.
bool PlyReader::nextLine(std::string& line) {
    Source& in = *source_;
    size_t scanned = 0;
    for (;;) {
        const char* d = in.data();
        const size_t avail = in.available();
        if (const void* nl = std::memchr(d + scanned, '\n', avail - scanned)) {
            const size_t length = size_t(static_cast<const char*>(nl) - d);
            line.assign(d, length);
            in.consume(length + 1);
            if (!line.empty() && line.back() == '\r') line.pop_back();
            return true;
        }
        scanned = avail;
        if (avail >= Source::kBufferSize) fail("a header line is longer than 1 MiB");
        if (in.fill(avail + 1) <= avail) return false;
    }
}

std::vector<std::string_view> words(std::string_view line) {
    std::vector<std::string_view> out;
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
        const size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
        if (i > start) out.push_back(line.substr(start, i - start));
    }
    return out;
}

void PlyReader::parseHeader() {
    // The magic first, so that any other file is named as such, whatever it holds.
    const bool magic = source_->fill(4) >= 4 && std::memcmp(source_->data(), "ply", 3) == 0 &&
                       (source_->data()[3] == '\n' || source_->data()[3] == '\r');
    if (!magic) fail("is not a PLY file (its first line is not 'ply')");
    std::string line;
    bool haveFormat = false;
    for (int lineNo = 1;; ++lineNo) {
        if (!nextLine(line)) fail("the header ends before 'end_header' (truncated file?)");
        if (lineNo == 1) continue;  // "ply"
        const std::vector<std::string_view> w = words(line);
        const std::string where = "header line " + std::to_string(lineNo) + ": ";
        if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
        if (w[0] == "end_header") break;
        if (w[0] == "format") {
            if (w.size() != 3 || w[2] != "1.0") fail(where + "expected 'format <type> 1.0'");
            if (w[1] == "ascii")
                format_ = Format::Ascii;
            else if (w[1] == "binary_little_endian")
                format_ = Format::BinaryLittleEndian;
            else if (w[1] == "binary_big_endian")
                format_ = Format::BinaryBigEndian;
            else
                fail(where + "unknown format '" + std::string(w[1]) + "'");
            haveFormat = true;
        } else if (w[0] == "element") {
            Element e;
            if (w.size() != 3) fail(where + "expected 'element <name> <count>'");
            e.name = w[1];
            const auto [end, ec] = std::from_chars(w[2].data(), w[2].data() + w[2].size(), e.count);
            if (ec != std::errc() || end != w[2].data() + w[2].size())
                fail(where + "element count '" + std::string(w[2]) + "' is not a whole number");
            for (const Element& other : elements_)
                if (other.name == e.name) fail(where + "a second element '" + e.name + "'");
            elements_.push_back(std::move(e));
        } else if (w[0] == "property") {
            if (elements_.empty()) fail(where + "a property before any element");
            Property p;
            bool ok;
            if (w.size() == 5 && w[1] == "list") {
                p.list = true;
                ok = parseType(w[2], p.countType) && parseType(w[3], p.type) &&
                     isInteger(p.countType);
                p.name = w[4];
            } else {
                ok = w.size() == 3 && parseType(w[1], p.type);
                p.name = w.size() == 3 ? w[2] : std::string_view();
            }
            if (!ok)
                fail(where +
                     "expected 'property <type> <name>' or 'property list <integer type> "
                     "<type> <name>'");
            elements_.back().props.push_back(std::move(p));
        } else if (!elements_.empty()) {
            // A line we do not understand among the element declarations may
            // be a property we would then misread every value after: an error.
            fail(where + "unknown keyword '" + std::string(w[0]) + "'");
        }
        // Before the first element, a stray line is a comment without the
        // keyword (Blender 2.4's exporter wrote its credit line that way).
        // It declares nothing, so reading past it is safe.
    }
    if (!haveFormat) fail("the header has no 'format' line");
    bodySize_ = fileSize_ - std::min(fileSize_, source_->offset());
}

void PlyReader::checkHeader() {
    for (Element& e : elements_) {
        if (e.name == "vertex") vertex_ = &e;
        if (e.name == "face") face_ = &e;
    }
    if (!vertex_) fail("has no 'vertex' element");
    if (!face_ || face_->count == 0) fail("has no faces (only points?)");
    if (vertex_->count > std::numeric_limits<uint32_t>::max())
        fail("has more vertices than 32-bit indices can address");

    auto claim = [&](const char* name, int slot) {
        Property* p = vertex_->find(name);
        if (p && !p->list) p->slot = slot;
        return p && !p->list;
    };
    if (!claim("x", kX) || !claim("y", kY) || !claim("z", kZ))
        fail("the vertex element lacks one of the scalar properties x, y, z");
    if (vertex_->find("nx") && vertex_->find("ny") && vertex_->find("nz"))
        hasNormals_ = claim("nx", kNx) && claim("ny", kNy) && claim("nz", kNz);
    // The uv names pbrt-v4's ReadPLY accepts, in its order of preference.
    static constexpr const char* uvNames[][2] = {
        {"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}};
    for (const auto& [u, v] : uvNames)
        if (!hasUvs_ && vertex_->find(u) && vertex_->find(v))
            hasUvs_ = claim(u, kU) && claim(v, kV);

    Property* indices = face_->find("vertex_indices");
    if (!indices) indices = face_->find("vertex_index");
    if (!indices || !indices->list || !isInteger(indices->type))
        fail("the face element has no integer list property 'vertex_indices'");
    indices->slot = kIndices;

    // Every instance takes some bytes, so the counts cannot exceed what the
    // body holds: this bounds the memory reserved below, whatever the header says.
    const uint64_t body = bodySize_;
    for (const Element* e : {vertex_, face_}) {
        size_t least = 0;
        for (const Property& p : e->props) {
            const size_t values = p.slot == kIndices ? 4 : 1;  // count + 3 indices
            least += format_ == Format::Ascii ? 2 * values
                                              : (p.list ? typeSize(p.countType) : 0) +
                                                    (values - p.list) * typeSize(p.type);
        }
        if (e->count > (body + 1) / least)
            fail("the " + e->name + " element declares " + std::to_string(e->count) +
                 " entries, more than the file holds (truncated file?)");
    }
}

template <typename In>
void PlyReader::skipList(In& in, const Property& p) {
    const int64_t n = in.integer(p.countType);
    if (n < 0) fail("a negative list length in element property '" + p.name + "'");
    for (int64_t k = 0; k < n; ++k) in.skip(p.type);
}

template <typename In>
void PlyReader::skipInstance(In& in, const Element& e) {
    for (const Property& p : e.props) {
        if (p.list)
            skipList(in, p);
        else
            in.skip(p.type);
    }
}

template <typename In>
void PlyReader::readVertices(In& in, const Element& e) {
    mesh_.positions.reserve(e.count + 1);  // + 1: see reserveForSharing
    mesh_.positions.resize(e.count);
    if (hasNormals_) mesh_.normals.resize(e.count);
    if (hasUvs_) mesh_.uvs.resize(e.count);
    float v[kSlots] = {};
    for (size_t i = 0; i < e.count; ++i) {
        for (const Property& p : e.props) {
            if (p.list)
                skipList(in, p);
            else if (p.slot >= 0)
                v[p.slot] = float(in.real(p.type));
            else
                in.skip(p.type);
        }
        bool finite = true;
        for (float x : v) finite &= std::isfinite(x);
        if (!finite)
            fail("vertex " + std::to_string(i) + " has a non-finite position, normal or uv");
        mesh_.positions[i] = {v[kX], v[kY], v[kZ]};
        if (hasNormals_) mesh_.normals[i] = {v[kNx], v[kNy], v[kNz]};
        if (hasUvs_) mesh_.uvs[i] = {v[kU], v[kV]};
    }
}

template <typename In>
void PlyReader::readFaces(In& in, const Element& e) {
    const int64_t nv = int64_t(vertex_->count);
    mesh_.indices.reserve(3 * e.count + 1);
    for (size_t i = 0; i < e.count; ++i) {
        for (const Property& p : e.props) {
            if (p.slot != kIndices) {
                if (p.list)
                    skipList(in, p);
                else
                    in.skip(p.type);
                continue;
            }
            const int64_t n = in.integer(p.countType);
            if (n != 3 && n != 4)
                fail("face " + std::to_string(i) + " has " + std::to_string(n) +
                     " vertices; pbrt-v4 reads only triangles and quads");
            uint32_t v[4];
            for (int k = 0; k < n; ++k) {
                const int64_t index = in.integer(p.type);
                if (index < 0 || index >= nv)
                    fail("face " + std::to_string(i) + ": vertex index " + std::to_string(index) +
                         " is out of range (" + std::to_string(nv) + " vertices)");
                v[k] = uint32_t(index);
            }
            mesh_.indices.insert(mesh_.indices.end(), {v[0], v[1], v[2]});
            if (n == 4) mesh_.indices.insert(mesh_.indices.end(), {v[0], v[2], v[3]});
        }
    }
}

template <typename In>
void PlyReader::readBody(In in) {
    for (const Element& e : elements_) {
        if (e.props.empty()) continue;  // nothing to read, however many there are
        try {
            if (&e == vertex_) {
                readVertices(in, e);
            } else if (&e == face_) {
                readFaces(in, e);
            } else {
                for (uint64_t i = 0; i < e.count; ++i) skipInstance(in, e);
            }
        } catch (const Truncated&) {
            fail("the file ends inside the '" + e.name + "' element (truncated file?)");
        } catch (const NotANumber& bad) {
            fail("'" + bad.token.substr(0, 40) + "' in the '" + e.name +
                 "' element is not a number");
        }
    }
}

Mesh PlyReader::read() {
    try {
        open();
        parseHeader();
        checkHeader();
        constexpr bool littleHost = std::endian::native == std::endian::little;
        switch (format_) {
            case Format::Ascii:
                readBody(AsciiInput(*source_));
                break;
            case Format::BinaryLittleEndian:
                readBody(BinaryInput<!littleHost>(*source_));
                break;
            case Format::BinaryBigEndian:
                readBody(BinaryInput<littleHost>(*source_));
                break;
        }
    } catch (const ReadError&) {
        fail("cannot be read");
    }
    mesh_.name = fs::path(path_).filename().string();
    return std::move(mesh_);
}

}  // namespace

Mesh loadPlyMesh(const std::string& path) {
    return PlyReader(path).read();
}

}  // namespace pathlab::pbrt
