// PLY strands: element vertex (x, y, z and optional red, green, blue, alpha) and element
// strand with one integer count property (nsegs: segments per strand, points = nsegs + 1).
// Files with no strand element (NeuralHaircut and similar: vertices only, every strand
// the same length) are read with pointsPerStrand: strands of N consecutive vertices.
// ascii, binary_little_endian and binary_big_endian; other elements and properties,
// list properties included, are skipped generically. A triangle mesh (element face, no
// strands) is refused with a pointer to mesh=, which reads it with parsePlyMesh: element
// vertex (x, y, z, optional nx, ny, nz) and element face (list vertex_indices; polygons
// as triangle fans).
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <sstream>

#include "scenes/loader_util.h"
#include "scenes/mesh_loaders.h"
#include "scenes/scene.h"

namespace sb {

namespace {

enum class Format { Ascii, BinaryLE, BinaryBE };

struct Type {
  int size = 0;  // bytes; 0 = invalid
  bool isFloat = false;
  bool isSigned = false;
};

Type typeFromName(const std::string& t) {
  if (t == "char" || t == "int8") return {1, false, true};
  if (t == "uchar" || t == "uint8") return {1, false, false};
  if (t == "short" || t == "int16") return {2, false, true};
  if (t == "ushort" || t == "uint16") return {2, false, false};
  if (t == "int" || t == "int32") return {4, false, true};
  if (t == "uint" || t == "uint32") return {4, false, false};
  if (t == "float" || t == "float32") return {4, true, true};
  if (t == "double" || t == "float64") return {8, true, true};
  return {};
}

struct Property {
  std::string name;
  Type type;
  bool isList = false;
  Type countType;
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> props;
};

// Sequential reader over the body; every read is bounds-checked.
class BodyReader {
 public:
  BodyReader(const uint8_t* data, std::size_t size, std::size_t pos, Format format,
             const std::string& name)
      : data_(data), size_(size), pos_(pos), format_(format), name_(name) {}

  std::size_t remaining() const { return size_ - pos_; }

  double read(const Type& t, const std::string& what) {
    return format_ == Format::Ascii ? readAscii(t, what) : readBinary(t, what);
  }

  // Skips n values of type t (list items we do not need).
  void skip(uint64_t n, const Type& t, const std::string& what) {
    if (format_ != Format::Ascii) {
      if (n > remaining() / uint64_t(t.size)) {
        detail::fail(name_, "truncated: list " + what + " has " + std::to_string(n) +
                                " items but only " + std::to_string(remaining()) + " bytes remain");
      }
      pos_ += std::size_t(n) * std::size_t(t.size);
      return;
    }
    for (uint64_t i = 0; i < n; ++i) readAscii(t, what);
  }

  // Reads n values of type t into out (a list we need: a face's vertex indices).
  void readList(uint64_t n, const Type& t, const std::string& what, std::vector<double>& out) {
    // Each value takes its size (binary) or at least one character (ascii): checked
    // before the allocation.
    if (n > remaining() / uint64_t(format_ == Format::Ascii ? 1 : t.size)) {
      detail::fail(name_, "truncated: list " + what + " has " + std::to_string(n) +
                              " items but only " + std::to_string(remaining()) + " bytes remain");
    }
    out.resize(std::size_t(n));
    for (double& v : out) v = read(t, what);
  }

 private:
  double readBinary(const Type& t, const std::string& what) {
    if (remaining() < std::size_t(t.size)) {
      detail::fail(name_, "truncated: the file ends while reading " + what);
    }
    uint8_t b[8];
    std::memcpy(b, data_ + pos_, std::size_t(t.size));
    pos_ += std::size_t(t.size);
    if (format_ == Format::BinaryBE) {
      for (int i = 0; i < t.size / 2; ++i) std::swap(b[i], b[t.size - 1 - i]);
    }
    if (t.isFloat) {
      if (t.size == 4) {
        float f;
        std::memcpy(&f, b, 4);
        return f;
      }
      double d;
      std::memcpy(&d, b, 8);
      return d;
    }
    uint64_t u = 0;
    for (int i = t.size - 1; i >= 0; --i) u = (u << 8) | b[i];
    if (t.isSigned) {
      const uint64_t signBit = uint64_t(1) << (8 * t.size - 1);
      if (u & signBit) return double(int64_t(u) - int64_t(signBit) - int64_t(signBit));
    }
    return double(u);
  }

  double readAscii(const Type& t, const std::string& what) {
    while (pos_ < size_ && std::isspace(data_[pos_])) ++pos_;
    const std::size_t start = pos_;
    while (pos_ < size_ && !std::isspace(data_[pos_])) ++pos_;
    if (start == pos_) detail::fail(name_, "truncated: the file ends while reading " + what);
    const char* first = reinterpret_cast<const char*>(data_ + start);
    const char* last = reinterpret_cast<const char*>(data_ + pos_);
    const std::string token(first, last);
    if (t.isFloat) {
      double d = 0;
      auto r = std::from_chars(first, last, d);
      if (r.ec != std::errc() || r.ptr != last) {
        detail::fail(name_, "'" + token.substr(0, 40) + "' is not a number (" + what + ")");
      }
      return d;
    }
    int64_t v = 0;
    auto r = std::from_chars(first, last, v);
    if (r.ec != std::errc() || r.ptr != last) {
      detail::fail(name_, "'" + token.substr(0, 40) + "' is not an integer (" + what + ")");
    }
    const int bits = 8 * t.size;
    const int64_t lo = t.isSigned ? -(int64_t(1) << (bits - 1)) : 0;
    const int64_t hi = t.isSigned ? (int64_t(1) << (bits - 1)) - 1 : (int64_t(1) << bits) - 1;
    if (v < lo || v > hi) {
      detail::fail(name_, "value " + token + " does not fit its type (" + what + ")");
    }
    return double(v);
  }

  const uint8_t* data_;
  std::size_t size_;
  std::size_t pos_;
  Format format_;
  const std::string& name_;
};

// "1 face", "2 faces".
std::string plural(uint64_t n, const std::string& noun) {
  return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

// An integer colour or alpha value in [0, 1] (its type's full range).
float unitFromInteger(double v, const Type& t) {
  const double maxv = double((uint64_t(1) << (8 * t.size)) - 1);
  return float(std::clamp(v / maxv, 0.0, 1.0));
}

float srgbToLinear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// The header: elements and properties in file order, the format, where the body starts.
struct Header {
  std::vector<Element> elements;
  Format format = Format::Ascii;
  std::size_t body = 0;
  const Element* find(const std::string& element) const {
    for (const Element& e : elements)
      if (e.name == element) return &e;
    return nullptr;
  }
};

Header parseHeader(const uint8_t* data, std::size_t size, const std::string& name) {
  using detail::fail;
  if (data == nullptr || size < 4 || std::memcmp(data, "ply", 3) != 0 ||
      (data[3] != '\n' && data[3] != '\r')) {
    fail(name, "not a PLY file (does not start with \"ply\")");
  }

  Header h;
  std::vector<Element>& elements = h.elements;
  Format& format = h.format;
  bool haveFormat = false, haveEnd = false;
  std::size_t pos = 0;
  int lineNo = 0;
  while (pos < size) {
    std::size_t eol = pos;
    while (eol < size && data[eol] != '\n') ++eol;
    std::string line(reinterpret_cast<const char*>(data + pos), eol - pos);
    pos = eol < size ? eol + 1 : size;
    ++lineNo;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (lineNo == 1) continue;  // "ply"
    std::istringstream ls(line);
    std::string kw;
    ls >> kw;
    const std::string where = "header line " + std::to_string(lineNo);
    if (kw.empty() || kw == "comment" || kw == "obj_info") continue;
    if (kw == "end_header") {
      haveEnd = true;
      break;
    }
    // A last line with no end of line is a file cut inside its header: say so, not what
    // the cut line's remnant would mean ("unknown property type ''").
    if (eol == size)
      fail(name, "truncated: the file ends inside its header, at " + where + " ('" +
                     line.substr(0, 40) + "'), before end_header");
    if (kw == "format") {
      std::string f, v;
      ls >> f >> v;
      if (f == "ascii") {
        format = Format::Ascii;
      } else if (f == "binary_little_endian") {
        format = Format::BinaryLE;
      } else if (f == "binary_big_endian") {
        format = Format::BinaryBE;
      } else {
        fail(name, where + ": unknown format '" + f + "'");
      }
      if (v != "1.0") fail(name, where + ": unsupported PLY version '" + v + "' (expected 1.0)");
      haveFormat = true;
    } else if (kw == "element") {
      Element e;
      std::string count, extra;
      ls >> e.name >> count;
      if (e.name.empty() || count.empty() || (ls >> extra)) {
        fail(name, where + ": expected 'element <name> <count>'");
      }
      auto r = std::from_chars(count.data(), count.data() + count.size(), e.count);
      if (r.ec != std::errc() || r.ptr != count.data() + count.size()) {
        fail(name, where + ": element count '" + count + "' is not a non-negative integer");
      }
      elements.push_back(std::move(e));
    } else if (kw == "property") {
      if (elements.empty()) fail(name, where + ": property before any element");
      Property p;
      std::string t;
      ls >> t;
      if (t == "list") {
        std::string ct, it;
        ls >> ct >> it >> p.name;
        p.isList = true;
        p.countType = typeFromName(ct);
        p.type = typeFromName(it);
        if (p.countType.size == 0 || p.countType.isFloat) {
          fail(name, where + ": list count type '" + ct + "' is not an integer type");
        }
        if (p.type.size == 0) fail(name, where + ": unknown list item type '" + it + "'");
      } else {
        ls >> p.name;
        p.type = typeFromName(t);
        if (p.type.size == 0) fail(name, where + ": unknown property type '" + t + "'");
      }
      if (p.name.empty()) fail(name, where + ": property without a name");
      elements.back().props.push_back(std::move(p));
    } else {
      fail(name, where + ": unknown header keyword '" + kw.substr(0, 40) + "'");
    }
  }
  if (!haveEnd) fail(name, "truncated: the file ends inside its header (no end_header line)");
  if (!haveFormat) fail(name, "PLY header has no format line");

  h.body = pos;
  return h;
}

// Reads the body's elements in file order: start(e) before an element's items, then
// item(e, i, values, list) for each: its scalar values by property index and, for the
// property `keep` (a list of e, or null), its items; every other list is skipped.
void readBody(const Header& h, const uint8_t* data, std::size_t size, const std::string& name,
              const Property* keep, const std::function<void(const Element&)>& start,
              const std::function<void(const Element&, uint64_t, const std::vector<double>&,
                                       const std::vector<double>&)>& item) {
  BodyReader in(data, size, h.body, h.format, name);
  std::vector<double> values, list;
  for (const Element& e : h.elements) {
    if (e.props.empty()) continue;  // no data to read
    // Cheap sanity check before any allocation or long loop: each item needs at least
    // this many bytes (binary) or one character (ascii).
    uint64_t minBytes = 0;
    for (const Property& p : e.props) minBytes += p.isList ? p.countType.size : p.type.size;
    if (h.format == Format::Ascii) minBytes = 1;
    if (e.count > in.remaining() / minBytes) {
      detail::fail(name, "truncated: element '" + e.name + "' declares " + std::to_string(e.count) +
                             " items but only " + std::to_string(in.remaining()) + " bytes remain");
    }
    start(e);
    values.assign(e.props.size(), 0.0);
    for (uint64_t i = 0; i < e.count; ++i) {
      for (std::size_t k = 0; k < e.props.size(); ++k) {
        const Property& p = e.props[k];
        if (p.isList) {
          const double n = in.read(p.countType, e.name + " list count '" + p.name + "'");
          if (n < 0) detail::fail(name, "negative list count in " + e.name + " '" + p.name + "'");
          const std::string what = "'" + p.name + "' of " + e.name;
          if (&p == keep)
            in.readList(uint64_t(n), p.type, what, list);
          else
            in.skip(uint64_t(n), p.type, what);
        } else {
          values[k] = in.read(p.type, e.name + " " + std::to_string(i) + " '" + p.name + "'");
        }
      }
      item(e, i, values, list);
    }
  }
}

// The index of scalar property `prop` of e, or -1; a list of that name is an error.
int findScalar(const Element& e, const char* prop, const std::string& name) {
  for (std::size_t i = 0; i < e.props.size(); ++i) {
    if (e.props[i].name == prop) {
      if (e.props[i].isList) detail::fail(name, std::string("property '") + prop + "' is a list");
      return int(i);
    }
  }
  return -1;
}

}  // namespace

Strands parsePly(const uint8_t* data, std::size_t size, const std::string& name,
                 uint32_t pointsPerStrand) {
  using detail::fail;
  const Header header = parseHeader(data, size, name);
  const std::vector<Element>& elements = header.elements;

  // --- locate the vertex, strand and face elements and their properties ---
  const Element* vertex = nullptr;
  const Element* strand = nullptr;
  const Element* face = nullptr;
  for (const Element& e : elements) {
    if (e.name == "vertex" && !vertex) vertex = &e;
    if ((e.name == "strand" || e.name == "strands") && !strand) strand = &e;
    if (e.name == "face" && !face) face = &e;
  }
  if (!vertex) fail(name, "PLY has no 'vertex' element");
  if (!strand && face && face->count > 0) {
    fail(name,
         "is a triangle mesh (element 'face', " + plural(face->count, "face") +
             ") with no strands; a mesh goes in mesh= (OBJ, PLY or TressFX .tfxmesh), strands in "
             "path=");
  }
  if (!strand && pointsPerStrand == 0) {
    fail(name, "PLY has no 'strand' element (segments per strand); if its " +
                   std::to_string(vertex->count) +
                   " vertices are strands of equal length one after another (NeuralHaircut "
                   "and similar), give points_per_strand=N");
  }
  if (strand && pointsPerStrand != 0) {
    fail(name, "has a 'strand' element (segments per strand), so points_per_strand=" +
                   std::to_string(pointsPerStrand) + " does not apply; leave it out");
  }
  if (vertex->count == 0) fail(name, "PLY has zero vertices");
  if (strand && strand->count == 0) fail(name, "PLY has zero strands");
  if (vertex->count > std::numeric_limits<uint32_t>::max()) {
    fail(name, "too many vertices (" + std::to_string(vertex->count) + ")");
  }
  if (!strand && vertex->count % pointsPerStrand != 0) {
    fail(name, "its " + std::to_string(vertex->count) +
                   (vertex->count == 1 ? " vertex is" : " vertices are") +
                   " not a whole number of strands of points_per_strand=" +
                   std::to_string(pointsPerStrand) + " points (" +
                   plural(vertex->count / pointsPerStrand, "strand") + " and " +
                   std::to_string(vertex->count % pointsPerStrand) + " left over)");
  }
  auto scalar = [&](const Element& e, const char* prop) { return findScalar(e, prop, name); };
  const int ix = scalar(*vertex, "x"), iy = scalar(*vertex, "y"), iz = scalar(*vertex, "z");
  if (ix < 0 || iy < 0 || iz < 0) fail(name, "vertex element lacks an x, y or z property");
  const int ir = scalar(*vertex, "red"), ig = scalar(*vertex, "green"),
            ib = scalar(*vertex, "blue");
  const bool hasColor = ir >= 0 && ig >= 0 && ib >= 0;
  const int ia = scalar(*vertex, "alpha");
  int ic = strand ? scalar(*strand, "nsegs") : 0;
  if (strand && ic < 0) {
    for (std::size_t i = 0; i < strand->props.size(); ++i) {
      if (!strand->props[i].isList && !strand->props[i].type.isFloat) {
        if (ic >= 0) fail(name, "strand element has no 'nsegs' and several integer properties");
        ic = int(i);
      }
    }
    if (ic < 0) fail(name, "strand element has no integer segment-count property (nsegs)");
  }
  if (strand && strand->props[std::size_t(ic)].type.isFloat) {
    fail(name,
         "strand property '" + strand->props[std::size_t(ic)].name + "' must be an integer type");
  }

  // --- body ---
  Strands s;
  auto start = [&](const Element& e) {
    if (&e == vertex) {
      s.points.resize(e.count);
      if (hasColor) s.colors.resize(e.count);
      if (ia >= 0) s.transparency.resize(e.count);
    }
    if (&e == strand) s.pointCount.resize(e.count);
  };
  auto item = [&](const Element& e, uint64_t i, const std::vector<double>& values,
                  const std::vector<double>&) {
    if (&e == vertex) {
      const glm::vec3 v{float(values[std::size_t(ix)]), float(values[std::size_t(iy)]),
                        float(values[std::size_t(iz)])};
      if (!detail::finite3(v)) {
        fail(name, "vertex " + std::to_string(i) + " has a NaN or infinite coordinate");
      }
      s.points[i] = v;
      if (hasColor) {
        glm::vec3 c;
        const int idx[3] = {ir, ig, ib};
        for (int j = 0; j < 3; ++j) {
          const std::size_t k = std::size_t(idx[j]);
          const Type& t = e.props[k].type;
          // Float colours are taken as linear, integer ones as sRGB.
          c[j] = t.isFloat ? float(values[k]) : srgbToLinear(unitFromInteger(values[k], t));
        }
        if (!detail::finite3(c)) {
          fail(name, "colour of vertex " + std::to_string(i) + " is NaN or infinite");
        }
        s.colors[i] = c;
      }
      if (ia >= 0) {
        // Alpha is opacity; the renderer's per-point transparency is 1 - alpha.
        const std::size_t k = std::size_t(ia);
        const Type& t = e.props[k].type;
        const double a = t.isFloat ? values[k] : double(unitFromInteger(values[k], t));
        if (std::isnan(a)) fail(name, "alpha of vertex " + std::to_string(i) + " is NaN");
        s.transparency[i] = 1.0f - float(std::clamp(a, 0.0, 1.0));
      }
    } else if (&e == strand) {
      const double n = values[std::size_t(ic)];
      if (n < 0) fail(name, "strand " + std::to_string(i) + " has a negative segment count");
      if (n >= double(std::numeric_limits<uint32_t>::max())) {
        fail(name, "strand " + std::to_string(i) + " has too many segments");
      }
      s.pointCount[i] = uint32_t(n) + 1;
    }
  };
  readBody(header, data, size, name, nullptr, start, item);

  if (!strand) s.pointCount.assign(std::size_t(vertex->count / pointsPerStrand), pointsPerStrand);
  uint64_t total = 0;
  s.firstPoint.resize(s.pointCount.size());
  for (std::size_t i = 0; i < s.pointCount.size(); ++i) {
    s.firstPoint[i] = uint32_t(std::min<uint64_t>(total, std::numeric_limits<uint32_t>::max()));
    total += s.pointCount[i];
  }
  if (total != vertex->count) {
    fail(name, "strand segment counts give " + std::to_string(total) +
                   " points (sum of nsegs + 1) but there are " + std::to_string(vertex->count) +
                   " vertices");
  }
  const std::size_t n = s.points.size();
  if (!hasColor) s.colors.assign(n, detail::kDefaultHairColor);
  s.thickness.assign(n, detail::kDefaultThickness);
  s.thicknessFallback = true;  // the format has none we read
  if (ia < 0) s.transparency.assign(n, 0.0f);
  return s;
}

}  // namespace sb

namespace sb {

Mesh parsePlyMesh(const uint8_t* data, std::size_t size, const std::string& name) {
  using detail::fail;
  const Header header = parseHeader(data, size, name);
  const Element* vertex = header.find("vertex");
  const Element* face = header.find("face");
  if (!vertex) fail(name, "PLY has no 'vertex' element");
  if (!face || face->count == 0) {
    fail(name, std::string("PLY has no faces (element 'face'): not a triangle mesh") +
                   (header.find("strand") ? "; strands go in path=" : ""));
  }
  if (vertex->count == 0) fail(name, "PLY has zero vertices");
  if (vertex->count > std::numeric_limits<uint32_t>::max()) {
    fail(name, "too many vertices (" + std::to_string(vertex->count) + ")");
  }
  auto scalar = [&](const Element& e, const char* prop) { return findScalar(e, prop, name); };
  const int ix = scalar(*vertex, "x"), iy = scalar(*vertex, "y"), iz = scalar(*vertex, "z");
  if (ix < 0 || iy < 0 || iz < 0) fail(name, "vertex element lacks an x, y or z property");
  const int inx = scalar(*vertex, "nx"), iny = scalar(*vertex, "ny"), inz = scalar(*vertex, "nz");
  const bool hasNormals = inx >= 0 && iny >= 0 && inz >= 0;
  // The face's vertex index list: "vertex_indices" (the PLY paper's name) or "vertex_index".
  const Property* indices = nullptr;
  for (const Property& p : face->props)
    if (p.isList && (p.name == "vertex_indices" || p.name == "vertex_index")) indices = &p;
  if (!indices) fail(name, "face element has no list property 'vertex_indices'");
  if (indices->type.isFloat) fail(name, "face property 'vertex_indices' must be an integer list");

  Mesh m;
  std::vector<glm::vec3> normals;
  auto start = [&](const Element& e) {
    if (&e != vertex) return;
    m.positions.resize(e.count);
    if (hasNormals) normals.resize(e.count);
  };
  auto item = [&](const Element& e, uint64_t i, const std::vector<double>& values,
                  const std::vector<double>& list) {
    auto vec = [&](int x, int y, int z) {
      return glm::vec3{float(values[std::size_t(x)]), float(values[std::size_t(y)]),
                       float(values[std::size_t(z)])};
    };
    if (&e == vertex) {
      m.positions[i] = vec(ix, iy, iz);
      if (!detail::finite3(m.positions[i]))
        fail(name, "vertex " + std::to_string(i) + " has a NaN or infinite coordinate");
      if (hasNormals && detail::finite3(vec(inx, iny, inz))) normals[i] = vec(inx, iny, inz);
    } else if (&e == face) {
      for (double v : list)
        if (v < 0 || v >= double(vertex->count))
          fail(name, "face " + std::to_string(i) + " refers to vertex " +
                         std::to_string(int64_t(v)) + ", which does not exist");
      // Polygons as fans of triangles (as the OBJ loader triangulates).
      for (std::size_t k = 2; k < list.size(); ++k)
        for (double v : {list[0], list[k - 1], list[k]}) m.indices.push_back(uint32_t(v));
    }
  };
  // The faces refer to the vertices: a file that stores them first cannot be read in one pass.
  if (face < vertex) fail(name, "element 'face' comes before element 'vertex'");
  readBody(header, data, size, name, indices, start, item);
  if (m.indices.empty()) fail(name, "PLY has no faces with three or more vertices");
  detail::setNormals(m, normals);
  return m;
}

}  // namespace sb
