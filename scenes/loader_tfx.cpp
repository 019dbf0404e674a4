// AMD TressFX .tfx, two forms:
//
// Binary (TressFX 3 and 4): float version, uint32 numStrands, uint32 numVerticesPerStrand,
// uint32 offsetVertexPosition, ... Version 3 files (bear.tfx) have a 296-byte header with
// float3 positions right after it (offsetVertexPosition 0); version 4 files
// (Ratboy_mohawk.tfx) have a 160-byte header and float4 positions at offsetVertexPosition,
// followed by optional blocks at the next four offsets (strand UVs float2[numStrands],
// vertex UVs float2[numPoints], strand thickness float[numStrands], vertex colours
// float4[numPoints]; 0 = absent). Only the positions are read; a file cut inside one of
// the later blocks is accepted with a warning.
//
// Text (TressFX 1.x/2.x samples and exporters), one item per line:
//   version 2.0                      (absent in 1.x files, which start at numStrands)
//   scale S / rotation X Y Z / translation X Y Z   (radians; applied as in AMD's loader:
//                                    scale, then roll Z, pitch X, yaw Y, then translate)
//   bothEndsImmovable, maxNumVerticesInStrand, numFollowHairsPerGuideHair,
//   maxRadiusAroundGuideHair, ... (simulation settings: checked, not used)
//   numStrands N
//   is sorted 1                      (ignored)
//   strand I numVerts M texcoord U V (N times, each followed by M lines "x y z")
// Values may also be separated by commas ("x, y, z"). Only the guide strands in the file
// are drawn (follow hairs are generated at run time by TressFX, as for the binary form).
//
// The .tfxmesh beside a .tfx (TressFX 4's exporter, Ratboy_body.tfxmesh) is text too:
// '#' comment lines; "numOfBones N" and N lines "index name"; "numOfVertices N" and N
// lines "index x y z nx ny nz" followed by four joint indices and four weights (skinning,
// not read); "numOfTriangles N" and N lines "index a b c".
#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <string_view>

#include "scenes/loader_util.h"
#include "scenes/mesh_loaders.h"
#include "scenes/scene.h"

namespace sb {

namespace {

// ---------------------------------------------------------------- text form

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// Whitespace- and comma-separated tokens of one line.
std::vector<std::string_view> tokenize(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (isSpace(line[i]) || line[i] == ',')) ++i;
    const std::size_t start = i;
    while (i < line.size() && !isSpace(line[i]) && line[i] != ',') ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

std::string_view skipBomAndSpace(std::string_view text) {
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  while (!text.empty() && (isSpace(text.front()) || text.front() == '\n')) text.remove_prefix(1);
  return text;
}

// The text form starts (after an optional UTF-8 BOM and blank space) with "version" or,
// in 1.x files, "numStrands", followed by blank space.
bool isTextTfx(const uint8_t* data, std::size_t size) {
  const std::string_view t =
      skipBomAndSpace(std::string_view(reinterpret_cast<const char*>(data), size));
  for (std::string_view kw : {std::string_view("version"), std::string_view("numStrands")}) {
    if (t.size() > kw.size() && t.substr(0, kw.size()) == kw && isSpace(t[kw.size()])) {
      return true;
    }
  }
  return false;
}

class TextReader {
 public:
  TextReader(const uint8_t* data, std::size_t size, const std::string& name)
      : text_(reinterpret_cast<const char*>(data), size), name_(name) {
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") text_.remove_prefix(3);
  }

  // The next line that is not blank, tokenized; false at the end of the file.
  bool next(std::vector<std::string_view>& tokens) {
    while (pos_ < text_.size()) {
      std::size_t eol = text_.find('\n', pos_);
      if (eol == std::string_view::npos) eol = text_.size();
      const std::string_view line = text_.substr(pos_, eol - pos_);
      pos_ = eol + 1;
      ++line_;
      tokens = tokenize(line);
      if (!tokens.empty()) return true;
    }
    return false;
  }

  int line() const { return line_; }

  [[noreturn]] void fail(const std::string& what) const {
    detail::fail(name_, "line " + std::to_string(line_) + ": " + what);
  }

  static std::string quote(std::string_view token) {
    std::string q = "'";
    q.append(token.substr(0, 40));
    if (token.size() > 40) q.append("...");
    q.push_back('\'');
    return q;
  }

  double number(std::string_view token, const std::string& what) const {
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    double v = 0;
    const auto r = std::from_chars(token.data(), token.data() + token.size(), v);
    if (token.empty() || r.ec != std::errc() || r.ptr != token.data() + token.size() ||
        !std::isfinite(v)) {
      fail(quote(token) + " is not a finite number (" + what + ")");
    }
    return v;
  }

  int64_t integer(std::string_view token, int64_t lo, int64_t hi, const std::string& what) const {
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    int64_t v = 0;
    const auto r = std::from_chars(token.data(), token.data() + token.size(), v);
    if (token.empty() || r.ec != std::errc() || r.ptr != token.data() + token.size()) {
      fail(quote(token) + " is not an integer (" + what + ")");
    }
    if (v < lo || v > hi) {
      fail(what + " " + std::to_string(v) + " is out of range [" + std::to_string(lo) + ", " +
           std::to_string(hi) + "]");
    }
    return v;
  }

  // Exactly n values after the keyword.
  void expectCount(const std::vector<std::string_view>& t, std::size_t n) const {
    if (t.size() != n + 1) {
      fail("'" + std::string(t[0].substr(0, 40)) + "' takes " + std::to_string(n) +
           (n == 1 ? " value" : " values") + ", not " + std::to_string(t.size() - 1));
    }
  }

 private:
  std::string_view text_;
  const std::string& name_;
  std::size_t pos_ = 0;
  int line_ = 0;
};

// Points per strand beyond which a text file is taken to be corrupt (as the generators'
// limit); the binary forms store 4..64.
constexpr int64_t kMaxTextVertsPerStrand = 100'000;

Strands parseTfxText(const uint8_t* data, std::size_t size, const std::string& name) {
  TextReader in(data, size, name);
  std::vector<std::string_view> t;
  float scale = 1.0f;
  glm::vec3 rotation(0.0f), translation(0.0f);
  int64_t numStrands = -1;
  bool first = true, atStrand = false;

  // --- header: keyword lines up to the first "strand" line ---
  while (in.next(t)) {
    const std::string_view kw = t[0];
    if (kw == "strand") {
      atStrand = true;
      break;
    }
    if (first && kw != "version" && kw != "numStrands") {
      in.fail("expected 'version' or 'numStrands' first, not " + TextReader::quote(kw));
    }
    first = false;
    if (kw == "version") {
      in.expectCount(t, 1);
      const double v = in.number(t[1], "version");
      if (!(v >= 1.0 && v < 3.0)) {
        in.fail("text TressFX version " + std::string(t[1].substr(0, 40)) +
                " is not 1.x or 2.x (binary .tfx files are versions 3 and 4)");
      }
    } else if (kw == "scale") {
      in.expectCount(t, 1);
      scale = float(in.number(t[1], "scale"));
    } else if (kw == "rotation" || kw == "translation") {
      in.expectCount(t, 3);
      glm::vec3& v = kw == "rotation" ? rotation : translation;
      for (int i = 0; i < 3; ++i) v[i] = float(in.number(t[std::size_t(i) + 1], std::string(kw)));
    } else if (kw == "bothEndsImmovable" || kw == "maxNumVerticesInStrand" ||
               kw == "numFollowHairsPerGuideHair") {
      in.expectCount(t, 1);
      in.integer(t[1], 0, std::numeric_limits<int32_t>::max(), std::string(kw));
    } else if (kw == "maxRadiusAroundGuideHair" || kw == "tipSeparation") {
      in.expectCount(t, 1);
      in.number(t[1], std::string(kw));
    } else if (kw == "numStrands") {
      in.expectCount(t, 1);
      numStrands = in.integer(t[1], 1, std::numeric_limits<uint32_t>::max(), "numStrands");
    } else if (kw == "is") {
      // "is sorted 1": how the exporter ordered the strands; nothing to draw.
      if (t.size() != 3 || t[1] != "sorted") in.fail("expected 'is sorted <0 or 1>'");
      in.integer(t[2], 0, 1, "is sorted");
    } else {
      const char c = kw[0];
      if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'))) {
        in.fail("expected a header keyword or 'strand', not " + TextReader::quote(kw));
      }
      // Another exporter's setting (a keyword and its values): not needed to draw.
    }
  }
  if (first) detail::fail(name, "empty text TressFX file");
  if (numStrands < 0) {
    in.fail("no 'numStrands' line before the first strand (or the end of the file)");
  }
  if (!atStrand) {
    detail::fail(name, "truncated: numStrands says " + std::to_string(numStrands) +
                           " strands but the file ends after its header");
  }

  // --- strands ---
  Strands s;
  const glm::mat3 rx = glm::mat3(1, 0, 0, 0, std::cos(rotation.x), std::sin(rotation.x), 0,
                                 -std::sin(rotation.x), std::cos(rotation.x));
  const glm::mat3 ry = glm::mat3(std::cos(rotation.y), 0, -std::sin(rotation.y), 0, 1, 0,
                                 std::sin(rotation.y), 0, std::cos(rotation.y));
  const glm::mat3 rz = glm::mat3(std::cos(rotation.z), std::sin(rotation.z), 0,
                                 -std::sin(rotation.z), std::cos(rotation.z), 0, 0, 0, 1);
  const glm::mat3 rotate = ry * rx * rz;  // roll (z) first, then pitch (x), then yaw (y)
  for (int64_t k = 0; k < numStrands; ++k) {
    const std::string which = "strand " + std::to_string(k);
    if (k > 0 && !in.next(t)) {
      detail::fail(name, "truncated: numStrands says " + std::to_string(numStrands) +
                             " strands but the file ends after " + std::to_string(k) + " (line " +
                             std::to_string(in.line()) + ")");
    }
    if (t[0] != "strand") {
      in.fail("expected 'strand <index> numVerts <count>' for " + which + ", not " +
              TextReader::quote(t[0]));
    }
    if (t.size() < 4 || t[2] != "numVerts") {
      in.fail("expected 'strand <index> numVerts <count> [texcoord <u> <v>]'");
    }
    in.integer(t[1], 0, std::numeric_limits<uint32_t>::max(), "strand index");
    const int64_t verts = in.integer(t[3], 1, kMaxTextVertsPerStrand, "numVerts of " + which);
    if (t.size() != 4) {
      if (t.size() != 7 || t[4] != "texcoord") {
        in.fail("after 'numVerts " + std::to_string(verts) +
                "' only 'texcoord <u> <v>' may follow");
      }
      in.number(t[5], "texcoord u");
      in.number(t[6], "texcoord v");
    }
    if (s.points.size() + uint64_t(verts) > std::numeric_limits<uint32_t>::max()) {
      in.fail("too many vertices in all");
    }
    s.firstPoint.push_back(uint32_t(s.points.size()));
    s.pointCount.push_back(uint32_t(verts));
    for (int64_t v = 0; v < verts; ++v) {
      if (!in.next(t)) {
        detail::fail(name, "truncated: " + which + " declares " + std::to_string(verts) +
                               " vertices but the file ends after " + std::to_string(v));
      }
      if (t.size() != 3) {
        in.fail("expected 3 numbers 'x y z' (vertex " + std::to_string(v) + " of " + which +
                ", which declares " + std::to_string(verts) + "), not " + std::to_string(t.size()) +
                " items starting " + TextReader::quote(t[0]));
      }
      glm::vec3 p;
      for (int i = 0; i < 3; ++i) p[i] = float(in.number(t[std::size_t(i)], "x y z"));
      p = rotate * (scale * p) + translation;
      if (!detail::finite3(p)) {
        in.fail("the vertex is not finite after scale, rotation and translation");
      }
      s.points.push_back(p);
    }
  }
  if (in.next(t)) {
    in.fail("more data after the " + std::to_string(numStrands) +
            " strands that numStrands declares, starting " + TextReader::quote(t[0]));
  }
  const std::size_t n = s.points.size();
  s.colors.assign(n, detail::kDefaultHairColor);
  s.thickness.assign(n, detail::kDefaultThickness);
  s.thicknessFallback = true;  // the format has none we read
  s.transparency.assign(n, 0.0f);
  return s;
}

// ---------------------------------------------------------------- binary form

// True when the first bytes read as text (printable ASCII and blank space).
bool looksLikeText(const uint8_t* data, std::size_t size) {
  const std::size_t n = std::min<std::size_t>(size, 16);
  for (std::size_t i = 0; i < n; ++i) {
    const uint8_t c = data[i];
    if (!((c >= 0x20 && c < 0x7f) || c == '\n' || c == '\r' || c == '\t')) return false;
  }
  return n > 0;
}

// Version 4: the blocks after the positions that this loader does not read. A block that
// runs past the end of the file is reported, not fatal: the positions are complete.
void warnCutBlocks(const uint8_t* data, std::size_t size, uint64_t numStrands, uint64_t numPoints,
                   const std::string& name, std::vector<std::string>* warnings) {
  if (!warnings) return;
  struct Block {
    std::size_t at;  // offset of its offset in the header
    const char* what;
    uint64_t bytes;
  };
  const Block blocks[] = {{16, "strand UV", numStrands * 8},
                          {20, "vertex UV", numPoints * 8},
                          {24, "strand thickness", numStrands * 4},
                          {28, "vertex colour", numPoints * 16}};
  for (const Block& b : blocks) {
    const uint64_t offset = detail::rdU32(data + b.at);
    if (offset == 0 || offset + b.bytes <= size) continue;
    warnings->push_back(name + ": truncated: the " + b.what + " block needs " +
                        std::to_string(b.bytes) + " bytes at offset " + std::to_string(offset) +
                        " but the file ends at " + std::to_string(size) +
                        "; that block is not used here and the positions are complete, so the "
                        "file is drawn as it is");
  }
}

}  // namespace

Strands parseTfx(const uint8_t* data, std::size_t size, const std::string& name,
                 std::vector<std::string>* warnings) {
  using detail::fail;
  if (data != nullptr && isTextTfx(data, size)) return parseTfxText(data, size, name);
  if (data == nullptr || size < 16) {
    fail(name, "too short for a TressFX header (" + std::to_string(size) + " bytes)");
  }
  const float version = detail::rdF32(data);
  uint64_t headerSize = 0, stride = 0;
  if (version == 3.0f) {
    headerSize = 296;
    stride = 12;
  } else if (version == 4.0f) {
    headerSize = 160;
    stride = 16;
  } else if (looksLikeText(data, size)) {
    fail(name,
         "is text but not a TressFX text file (its first line should be 'version 2.0' "
         "or 'numStrands N'), nor a binary .tfx (version 3 or 4)");
  } else {
    fail(name,
         "unsupported TressFX version " +
             (std::isfinite(version) ? std::to_string(version) : std::string("(not a number)")) +
             " (expected 3.0 or 4.0)");
  }
  if (size < headerSize) {
    fail(name, "truncated: the version " + std::to_string(int(version)) + " header needs " +
                   std::to_string(headerSize) + " bytes but the file has " + std::to_string(size));
  }
  const uint64_t numStrands = detail::rdU32(data + 4);
  const uint64_t perStrand = detail::rdU32(data + 8);
  uint64_t offset = detail::rdU32(data + 12);
  if (numStrands == 0) fail(name, "header says zero strands");
  if (perStrand == 0) fail(name, "header says zero vertices per strand");
  if (offset == 0) offset = headerSize;
  if (offset < headerSize) {
    fail(name, "vertex position offset " + std::to_string(offset) + " lies inside the " +
                   std::to_string(headerSize) + "-byte header");
  }
  const uint64_t numPoints = numStrands * perStrand;  // < 2^64: both are 32-bit
  if (numPoints > std::numeric_limits<uint32_t>::max() || offset > size ||
      numPoints > (size - offset) / stride) {
    fail(name, "truncated: " + std::to_string(numStrands) + " strands x " +
                   std::to_string(perStrand) + " vertices need " +
                   std::to_string(numPoints * stride) + " bytes of positions at offset " +
                   std::to_string(offset) + " but the file has " + std::to_string(size));
  }

  Strands s;
  s.firstPoint.resize(numStrands);
  s.pointCount.assign(numStrands, uint32_t(perStrand));
  for (uint64_t i = 0; i < numStrands; ++i) s.firstPoint[i] = uint32_t(i * perStrand);
  s.points.resize(numPoints);
  const uint8_t* p = data + offset;
  for (uint64_t i = 0; i < numPoints; ++i) {
    const uint8_t* q = p + stride * i;
    s.points[i] = glm::vec3(detail::rdF32(q), detail::rdF32(q + 4), detail::rdF32(q + 8));
    if (!detail::finite3(s.points[i])) {
      fail(name, "vertex " + std::to_string(i) + " has a NaN or infinite coordinate");
    }
  }
  if (version == 4.0f) warnCutBlocks(data, size, numStrands, numPoints, name, warnings);
  s.colors.assign(numPoints, detail::kDefaultHairColor);
  s.thickness.assign(numPoints, detail::kDefaultThickness);
  s.thicknessFallback = true;  // the format has none we read
  s.transparency.assign(numPoints, 0.0f);
  return s;
}

Mesh parseTfxMesh(const uint8_t* data, std::size_t size, const std::string& name) {
  TextReader in(data, size, name);
  std::vector<std::string_view> t;
  auto next = [&] {  // the next line that is not a '#' comment
    while (in.next(t))
      if (t[0].front() != '#') return true;
    return false;
  };
  constexpr const char* kLayout =
      "a TressFX .tfxmesh has numOfBones N, numOfVertices N and numOfTriangles N, each followed "
      "by its N lines";
  // "keyword N", then N lines of at least `values` values, the first the line's index.
  auto block = [&](const std::string& keyword, std::size_t values, const std::string& what,
                   const auto& take) {
    if (!next()) detail::fail(name, "ends before '" + keyword + "' (" + kLayout + ")");
    if (t[0] != keyword)
      in.fail("expected '" + keyword + " N', found " + TextReader::quote(t[0]) + " (" + kLayout +
              ")");
    in.expectCount(t, 1);
    const int64_t n = in.integer(t[1], 0, std::numeric_limits<uint32_t>::max(), keyword);
    for (int64_t i = 0; i < n; ++i) {
      if (!next())
        detail::fail(name, "ends after " + std::to_string(i) + " of the " + std::to_string(n) +
                               " lines of " + keyword);
      if (t.size() < values)
        in.fail(what + " " + std::to_string(i) + " has " + std::to_string(t.size()) +
                " values, not " + std::to_string(values) + " or more");
      if (in.integer(t[0], 0, n - 1, what + " index") != i)
        in.fail(what + " index " + std::string(t[0]) + " where " + std::to_string(i) +
                " was expected");
      take();
    }
  };
  Mesh m;
  std::vector<glm::vec3> normals;
  auto vec = [&](std::size_t at, const char* what) {
    const glm::vec3 v(in.number(t[at], what), in.number(t[at + 1], what),
                      in.number(t[at + 2], what));
    // Finite as a double, a value can still overflow a float (1e300).
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
      in.fail(std::string(what) + " is too large for a float");
    return v;
  };
  block("numOfBones", 2, "bone", [] {});  // skinning: not drawn
  // index, position, normal, then joints and weights (skinning: not read).
  block("numOfVertices", 7, "vertex", [&] {
    m.positions.push_back(vec(1, "vertex position"));
    normals.push_back(vec(4, "vertex normal"));
  });
  block("numOfTriangles", 4, "triangle", [&] {
    for (std::size_t k = 1; k <= 3; ++k)
      m.indices.push_back(uint32_t(in.integer(
          t[k], 0, int64_t(m.positions.size()) - 1,
          "triangle vertex index (of " + std::to_string(m.positions.size()) + " vertices)")));
  });
  if (m.indices.empty()) detail::fail(name, "has no triangles");
  detail::setNormals(m, normals);
  return m;
}

}  // namespace sb
