// SPDX-License-Identifier: MIT
#include "mesh_formats.h"

#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string_view>
#include <utility>
#include <vector>

namespace sc::tools {

namespace {

using Position = std::array<double, 3>;

/// What a reader collects: positions and triangles indexing them.
struct Polygons {
  std::vector<Position> positions;
  std::vector<sc::Tri> triangles;
  int skipped = 0;
};

sc::Status bad(const std::string& what) { return {sc::ErrorCode::InvalidArgument, what}; }
std::string str(long long n) { return std::to_string(n); }

/// The lines of a byte range, without their ends (\n or \r\n).
class Lines {
 public:
  Lines(const char* data, std::size_t size) : data_(data), size_(size) {}
  bool done() const { return pos_ >= size_; }
  std::size_t offset() const { return pos_; }
  std::string_view next() {
    const char* start = data_ + pos_;
    const void* end = std::memchr(start, '\n', size_ - pos_);
    const std::size_t length = end != nullptr
                                   ? static_cast<std::size_t>(static_cast<const char*>(end) - start)
                                   : size_ - pos_;
    pos_ += length + (end != nullptr ? 1 : 0);
    std::string_view line(start, length);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    return line;
  }

 private:
  const char* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

/// The whitespace-separated tokens of `line`, up to a '#' when `comments`.
void split(std::string_view line, std::vector<std::string_view>& out, bool comments) {
  out.clear();
  if (comments) line = line.substr(0, line.find('#'));
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && isSpace(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !isSpace(line[i])) ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
}

/// A whole token as a number (strtod: "nan" and "inf" parse, the caller checks them).
bool parseReal(std::string_view token, double& out) {
  char buffer[72];
  if (token.empty() || token.size() >= sizeof buffer) return false;
  std::memcpy(buffer, token.data(), token.size());
  buffer[token.size()] = '\0';
  char* end = nullptr;
  out = std::strtod(buffer, &end);
  return end == buffer + token.size();
}

bool parseInteger(std::string_view token, long long& out) {
  char buffer[32];
  if (token.empty() || token.size() >= sizeof buffer) return false;
  std::memcpy(buffer, token.data(), token.size());
  buffer[token.size()] = '\0';
  char* end = nullptr;
  errno = 0;
  out = std::strtoll(buffer, &end, 10);
  return end == buffer + token.size() && errno == 0;
}

std::string quoted(std::string_view token) {
  return "'" + std::string(token.substr(0, 24)) + (token.size() > 24 ? "...'" : "'");
}

/// Three finite coordinates from tokens[first..first+2].
sc::Status readPosition(const std::vector<std::string_view>& tokens, std::size_t first,
                        const std::string& what, Polygons& out) {
  Position p;
  for (int k = 0; k < 3; ++k) {
    const std::string_view t = tokens[first + static_cast<std::size_t>(k)];
    if (!parseReal(t, p[k])) return bad(what + ": " + quoted(t) + " is not a number");
    if (!std::isfinite(p[k])) return bad(what + " is not finite (" + quoted(t) + ")");
  }
  out.positions.push_back(p);
  return sc::Status::success();
}

/// The polygon `ids` fanned into triangles; every id must name one of `count` vertices
/// (messages show ids plus `shown_base`: 1 for OBJ's 1-based indices).
sc::Status addPolygon(const std::vector<long long>& ids, long long count, const std::string& what,
                      Polygons& out, int shown_base = 0) {
  if (ids.size() < 3)
    return bad(what + " has " + str(static_cast<long long>(ids.size())) + " corners (at least 3)");
  for (long long id : ids)
    if (id < 0 || id >= count)
      return bad(what + " refers to vertex " + str(id + shown_base) + ", out of range (" +
                 str(count) + " vertices)");
  for (std::size_t k = 1; k + 1 < ids.size(); ++k)
    out.triangles.push_back(
        {static_cast<int>(ids[0]), static_cast<int>(ids[k]), static_cast<int>(ids[k + 1])});
  return sc::Status::success();
}

// ---------------------------------------------------------------- OFF

/// The next line holding data (comments stripped); false at the end of the file.
bool nextDataLine(Lines& lines, std::vector<std::string_view>& tokens) {
  while (!lines.done()) {
    split(lines.next(), tokens, true);
    if (!tokens.empty()) return true;
  }
  return false;
}

/// [ST][C][N]OFF: texture, colour and normal columns follow the coordinates.
bool isOffKeyword(std::string_view word) {
  for (std::string_view prefix : {"ST", "C", "N"})
    if (word.substr(0, prefix.size()) == prefix) word.remove_prefix(prefix.size());
  return word == "OFF";
}

sc::Status readOffCounts(Lines& lines, std::vector<std::string_view>& tokens, long long& nv,
                         long long& nf) {
  if (!nextDataLine(lines, tokens)) return bad("empty file");
  if (!isOffKeyword(tokens[0])) return bad("no OFF header (found " + quoted(tokens[0]) + ")");
  std::size_t first = 1;  // the counts may follow the keyword on its line
  if (tokens.size() == 1) {
    if (!nextDataLine(lines, tokens)) return bad("no counts");
    first = 0;
  }
  if (tokens.size() < first + 2 || !parseInteger(tokens[first], nv) ||
      !parseInteger(tokens[first + 1], nf) || nv < 0 || nf < 0 || nv > INT32_MAX || nf > INT32_MAX)
    return bad("the counts line is not 'VERTICES FACES [EDGES]'");
  return sc::Status::success();
}

sc::Status readOff(const char* data, std::size_t size, Polygons& out) {
  Lines lines(data, size);
  std::vector<std::string_view> tokens;
  long long nv = 0, nf = 0;
  if (sc::Status s = readOffCounts(lines, tokens, nv, nf); !s.ok()) return s;
  for (long long i = 0; i < nv; ++i) {
    const std::string what = "vertex " + str(i);
    if (!nextDataLine(lines, tokens))
      return bad("the file ends after " + str(i) + " of " + str(nv) + " vertices");
    if (tokens.size() < 3) return bad(what + " has fewer than 3 coordinates");
    if (sc::Status s = readPosition(tokens, 0, what, out); !s.ok()) return s;
  }
  std::vector<long long> ids;
  for (long long i = 0; i < nf; ++i) {
    const std::string what = "face " + str(i);
    if (!nextDataLine(lines, tokens))
      return bad("the file ends after " + str(i) + " of " + str(nf) + " faces");
    long long corners = 0;
    if (!parseInteger(tokens[0], corners) || corners < 0)
      return bad(what + ": " + quoted(tokens[0]) + " is not a corner count");
    if (static_cast<std::size_t>(corners) > tokens.size() - 1)
      return bad(what + " promises " + str(corners) + " indices and lists " +
                 str(static_cast<long long>(tokens.size() - 1)));
    ids.resize(static_cast<std::size_t>(corners));
    for (std::size_t k = 0; k < ids.size(); ++k)
      if (!parseInteger(tokens[k + 1], ids[k]))
        return bad(what + ": " + quoted(tokens[k + 1]) + " is not an index");
    if (sc::Status s = addPolygon(ids, nv, what, out); !s.ok()) return s;
  }
  return sc::Status::success();
}

// ---------------------------------------------------------------- PLY

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };
enum class PlyFormat { Ascii, LittleEndian, BigEndian };

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;  ///< the item type of a list
  bool list = false;
  PlyType count_type = PlyType::UInt8;
};

struct PlyElement {
  std::string name;
  long long count = 0;
  std::vector<PlyProperty> properties;
};

bool plyTypeOf(std::string_view name, PlyType& type) {
  static const std::pair<const char*, PlyType> kNames[] = {
      {"char", PlyType::Int8},      {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
      {"uint8", PlyType::UInt8},    {"short", PlyType::Int16},     {"int16", PlyType::Int16},
      {"ushort", PlyType::UInt16},  {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
      {"int32", PlyType::Int32},    {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
      {"float", PlyType::Float32},  {"float32", PlyType::Float32}, {"double", PlyType::Float64},
      {"float64", PlyType::Float64}};
  for (const auto& [text, value] : kNames)
    if (name == text) {
      type = value;
      return true;
    }
  return false;
}

std::size_t plySize(PlyType t) {
  switch (t) {
    case PlyType::Int8:
    case PlyType::UInt8:
      return 1;
    case PlyType::Int16:
    case PlyType::UInt16:
      return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32:
      return 4;
    case PlyType::Float64:
      return 8;
  }
  return 1;
}

bool isInteger(PlyType t) { return t != PlyType::Float32 && t != PlyType::Float64; }

struct PlyHeader {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
};

sc::Status readPlyProperty(const std::vector<std::string_view>& t, PlyHeader& header) {
  if (header.elements.empty()) return bad("a property comes before any element");
  PlyProperty p;
  if (t.size() == 5 && t[1] == "list") {
    p.list = true;
    if (!plyTypeOf(t[2], p.count_type) || !plyTypeOf(t[3], p.type) || !isInteger(p.count_type))
      return bad("bad list property types " + quoted(t[2]) + " " + quoted(t[3]));
  } else if (t.size() != 3 || !plyTypeOf(t[1], p.type)) {
    return bad("bad property line (" + quoted(t.size() > 1 ? t[1] : t[0]) + ")");
  }
  p.name = std::string(t.back());
  header.elements.back().properties.push_back(std::move(p));
  return sc::Status::success();
}

sc::Status readPlyHeaderLine(const std::vector<std::string_view>& t, PlyHeader& header,
                             bool& has_format) {
  if (t.empty() || t[0] == "comment" || t[0] == "obj_info") return sc::Status::success();
  if (t[0] == "format") {
    if (t.size() != 3 || t[2].substr(0, 1) != "1") return bad("bad format line");
    if (t[1] == "ascii")
      header.format = PlyFormat::Ascii;
    else if (t[1] == "binary_little_endian")
      header.format = PlyFormat::LittleEndian;
    else if (t[1] == "binary_big_endian")
      header.format = PlyFormat::BigEndian;
    else
      return bad("unknown format " + quoted(t[1]));
    has_format = true;
    return sc::Status::success();
  }
  if (t[0] == "element") {
    PlyElement e;
    if (t.size() != 3 || !parseInteger(t[2], e.count) || e.count < 0 || e.count > INT32_MAX)
      return bad("bad element line");
    e.name = std::string(t[1]);
    header.elements.push_back(std::move(e));
    return sc::Status::success();
  }
  if (t[0] == "property") return readPlyProperty(t, header);
  return bad("unknown header line " + quoted(t[0]));
}

const PlyElement* findElement(const PlyHeader& header, const char* name) {
  for (const PlyElement& e : header.elements)
    if (e.name == name) return &e;
  return nullptr;
}

int findProperty(const PlyElement& e, std::string_view name, bool list) {
  for (std::size_t i = 0; i < e.properties.size(); ++i)
    if (e.properties[i].name == name && e.properties[i].list == list) return static_cast<int>(i);
  return -1;
}

/// The index of the face list: "vertex_indices" or "vertex_index", integer items.
int faceListOf(const PlyElement& face) {
  int i = findProperty(face, "vertex_indices", true);
  if (i < 0) i = findProperty(face, "vertex_index", true);
  return i >= 0 && isInteger(face.properties[static_cast<std::size_t>(i)].type) ? i : -1;
}

sc::Status checkPlyHeader(const PlyHeader& header) {
  int vertices = 0, faces = 0;
  for (const PlyElement& e : header.elements) {
    if (e.properties.empty()) return bad("element '" + e.name + "' has no properties");
    vertices += e.name == "vertex";
    faces += e.name == "face";
  }
  if (vertices > 1 || faces > 1) return bad("more than one 'vertex' or 'face' element");
  const PlyElement* vertex = findElement(header, "vertex");
  const PlyElement* face = findElement(header, "face");
  if (vertex == nullptr || face == nullptr) return bad("no 'vertex' or no 'face' element");
  for (const char* axis : {"x", "y", "z"})
    if (findProperty(*vertex, axis, false) < 0)
      return bad("the vertex element has no scalar '" + std::string(axis) + "'");
  if (faceListOf(*face) < 0) return bad("the face element has no integer vertex_indices list");
  return sc::Status::success();
}

sc::Status readPlyHeader(Lines& lines, PlyHeader& header) {
  std::vector<std::string_view> tokens;
  if (!lines.done()) split(lines.next(), tokens, false);
  if (tokens.size() != 1 || tokens[0] != "ply") return bad("no 'ply' first line");
  bool has_format = false;
  while (!lines.done()) {
    split(lines.next(), tokens, false);
    if (lines.done() && (tokens.empty() || tokens[0] != "end_header"))
      return bad("the header is cut off (no end_header line)");
    if (!tokens.empty() && tokens[0] == "end_header") {
      if (!has_format) return bad("no format line");
      return checkPlyHeader(header);
    }
    if (sc::Status s = readPlyHeaderLine(tokens, header, has_format); !s.ok()) return s;
  }
  return bad("the header has no end_header line");
}

/// The values of the element instances, in order: one line each in ASCII, packed
/// bytes in binary.
class PlyValues {
 public:
  PlyValues(const char* data, std::size_t size, std::size_t start, PlyFormat format)
      : lines_(data + start, size - start),
        data_(data),
        size_(size),
        pos_(start),
        format_(format) {}

  /// Starts an instance; false at the end of the file.
  bool begin() {
    if (format_ != PlyFormat::Ascii) return pos_ < size_;
    do {
      if (lines_.done()) return false;
      split(lines_.next(), tokens_, false);
    } while (tokens_.empty());
    next_token_ = 0;
    return true;
  }
  /// False when the instance has no more values or the value is not of `type`.
  bool value(PlyType type, double& out) {
    if (format_ == PlyFormat::Ascii) {
      if (next_token_ >= tokens_.size() || !parseReal(tokens_[next_token_++], out)) return false;
      return !isInteger(type) || (std::isfinite(out) && out == std::floor(out));
    }
    const std::size_t n = plySize(type);
    if (size_ - pos_ < n) return false;
    out = decode(type, reinterpret_cast<const unsigned char*>(data_ + pos_), n);
    pos_ += n;
    return true;
  }
  /// False when an ASCII line holds more values than the element's properties.
  bool end() const { return format_ != PlyFormat::Ascii || next_token_ == tokens_.size(); }

 private:
  double decode(PlyType type, const unsigned char* bytes, std::size_t n) const {
    std::uint64_t bits = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t shift = format_ == PlyFormat::LittleEndian ? i : n - 1 - i;
      bits |= static_cast<std::uint64_t>(bytes[i]) << (8 * shift);
    }
    switch (type) {
      case PlyType::Int8:
        return static_cast<std::int8_t>(bits);
      case PlyType::Int16:
        return static_cast<std::int16_t>(bits);
      case PlyType::Int32:
        return static_cast<std::int32_t>(bits);
      case PlyType::Float32: {
        const auto b32 = static_cast<std::uint32_t>(bits);
        float f;
        std::memcpy(&f, &b32, sizeof f);
        return f;
      }
      case PlyType::Float64: {
        double d;
        std::memcpy(&d, &bits, sizeof d);
        return d;
      }
      default:
        return static_cast<double>(bits);
    }
  }

  Lines lines_;
  const char* data_;
  std::size_t size_;
  std::size_t pos_;
  PlyFormat format_;
  std::vector<std::string_view> tokens_;
  std::size_t next_token_ = 0;
};

/// Reads one instance of `e`; positions of "vertex", polygons of "face".
sc::Status readPlyInstance(const PlyElement& e, long long i, long long vertex_count,
                           PlyValues& values, std::vector<long long>& ids, Polygons& out) {
  const std::string what = e.name + " " + str(i);
  if (!values.begin())
    return bad("the file ends after " + str(i) + " of " + str(e.count) + " " + e.name + "s");
  const bool is_vertex = e.name == "vertex";
  const int face_list = e.name == "face" ? faceListOf(e) : -1;
  Position p{};
  for (std::size_t k = 0; k < e.properties.size(); ++k) {
    const PlyProperty& prop = e.properties[k];
    double v = 0;
    if (!values.value(prop.list ? prop.count_type : prop.type, v))
      return bad(what + " is cut short or holds a bad value ('" + prop.name + "')");
    // An ASCII count is any whole number the text spells (3.7e33 is one): within
    // a 32-bit count, a cut-short list is found by reading it.
    if (prop.list && !(v >= 0 && v <= 2147483647.0))
      return bad(what + " has a bad item count in '" + prop.name + "'");
    if (!prop.list) {
      const int axis = prop.name == "x" ? 0 : prop.name == "y" ? 1 : prop.name == "z" ? 2 : -1;
      if (is_vertex && axis >= 0) p[static_cast<std::size_t>(axis)] = v;
      continue;
    }
    const bool keep = static_cast<int>(k) == face_list;
    if (keep) ids.clear();
    for (double n = 0; n < v; ++n) {
      double id = 0;
      if (!values.value(prop.type, id))
        return bad(what + " promises " + str(static_cast<long long>(v)) + " items in '" +
                   prop.name + "' and is cut short");
      if (keep) ids.push_back(static_cast<long long>(std::fmax(std::fmin(id, 1e15), -1e15)));
    }
  }
  if (!values.end()) return bad(what + " holds more values than its properties");
  if (is_vertex) {
    for (double c : p)
      if (!std::isfinite(c)) return bad(what + " is not finite");
    out.positions.push_back(p);
  }
  return face_list >= 0 ? addPolygon(ids, vertex_count, what, out) : sc::Status::success();
}

sc::Status readPly(const char* data, std::size_t size, Polygons& out) {
  Lines lines(data, size);
  PlyHeader header;
  if (sc::Status s = readPlyHeader(lines, header); !s.ok()) return s;
  const long long vertex_count = findElement(header, "vertex")->count;
  PlyValues values(data, size, lines.offset(), header.format);
  std::vector<long long> ids;
  for (const PlyElement& e : header.elements)
    for (long long i = 0; i < e.count; ++i)
      if (sc::Status s = readPlyInstance(e, i, vertex_count, values, ids, out); !s.ok()) return s;
  return sc::Status::success();
}

// ---------------------------------------------------------------- STL

constexpr std::size_t kStlHeader = 84;
constexpr std::size_t kStlTriangle = 50;

sc::Status readBinaryStl(const char* data, std::size_t size, Polygons& out) {
  const auto* bytes = reinterpret_cast<const unsigned char*>(data);
  for (std::size_t at = kStlHeader; at + kStlTriangle <= size; at += kStlTriangle) {
    const long long t = static_cast<long long>((at - kStlHeader) / kStlTriangle);
    for (std::size_t v = 0; v < 3; ++v) {
      Position p;
      for (std::size_t k = 0; k < 3; ++k) {
        const unsigned char* b = bytes + at + 12 + 12 * v + 4 * k;
        const std::uint32_t bits =
            b[0] | (b[1] << 8) | (b[2] << 16) | (static_cast<std::uint32_t>(b[3]) << 24);
        float f;
        std::memcpy(&f, &bits, sizeof f);
        if (!std::isfinite(f)) return bad("triangle " + str(t) + " is not finite");
        p[k] = f;
      }
      out.positions.push_back(p);
    }
    const int first = static_cast<int>(out.positions.size()) - 3;
    out.triangles.push_back({first, first + 1, first + 2});
  }
  return sc::Status::success();
}

/// The whitespace-separated words of an ASCII STL file.
class Words {
 public:
  Words(const char* data, std::size_t size) : data_(data), size_(size) {}
  std::string_view next() {
    while (pos_ < size_ && (isSpace(data_[pos_]) || data_[pos_] == '\n')) ++pos_;
    const std::size_t start = pos_;
    while (pos_ < size_ && !isSpace(data_[pos_]) && data_[pos_] != '\n') ++pos_;
    return {data_ + start, pos_ - start};
  }
  void skipLine() {
    while (pos_ < size_ && data_[pos_] != '\n') ++pos_;
  }

 private:
  const char* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

sc::Status expectWord(Words& words, std::string_view word, const std::string& what) {
  const std::string_view w = words.next();
  if (w == word) return sc::Status::success();
  return bad(what + ": expected '" + std::string(word) + "', found " +
             (w.empty() ? std::string("the end of the file") : quoted(w)));
}

sc::Status readStlFacet(Words& words, long long t, Polygons& out) {
  const std::string what = "facet " + str(t);
  std::vector<std::string_view> numbers(3);
  if (sc::Status s = expectWord(words, "normal", what); !s.ok()) return s;
  for (int k = 0; k < 3; ++k) words.next();
  if (sc::Status s = expectWord(words, "outer", what); !s.ok()) return s;
  if (sc::Status s = expectWord(words, "loop", what); !s.ok()) return s;
  for (int v = 0; v < 3; ++v) {
    if (sc::Status s = expectWord(words, "vertex", what); !s.ok()) return s;
    for (std::string_view& n : numbers) n = words.next();
    if (sc::Status s = readPosition(numbers, 0, what, out); !s.ok()) return s;
  }
  if (sc::Status s = expectWord(words, "endloop", what); !s.ok()) return s;
  if (sc::Status s = expectWord(words, "endfacet", what); !s.ok()) return s;
  const int first = static_cast<int>(out.positions.size()) - 3;
  out.triangles.push_back({first, first + 1, first + 2});
  return sc::Status::success();
}

sc::Status readAsciiStl(const char* data, std::size_t size, Polygons& out) {
  Words words(data, size);
  if (words.next() != "solid") return bad("no 'solid' first word");
  words.skipLine();  // the solid's name
  for (long long t = 0;;) {
    const std::string_view w = words.next();
    if (w == "facet") {
      if (sc::Status s = readStlFacet(words, t++, out); !s.ok()) return s;
    } else if (w == "endsolid") {
      words.skipLine();
      const std::string_view after = words.next();
      if (after.empty()) return sc::Status::success();
      if (after != "solid") return bad("unexpected " + quoted(after) + " after endsolid");
      words.skipLine();
    } else {
      return bad(w.empty() ? "the file ends without 'endsolid'"
                           : "expected 'facet' or 'endsolid', found " + quoted(w));
    }
  }
}

/// Binary when the size is exactly what the triangle count says; otherwise ASCII
/// when it starts with "solid" (binary headers may start so too).
sc::Status readStl(const char* data, std::size_t size, Polygons& out) {
  std::uint32_t count = 0;
  if (size >= kStlHeader) {
    const auto* b = reinterpret_cast<const unsigned char*>(data) + 80;
    count = b[0] | (b[1] << 8) | (b[2] << 16) | (static_cast<std::uint32_t>(b[3]) << 24);
    if (kStlHeader + kStlTriangle * static_cast<std::uint64_t>(count) == size)
      return readBinaryStl(data, size, out);
  }
  Words words(data, size);
  if (words.next() == "solid") return readAsciiStl(data, size, out);
  if (size < kStlHeader) return bad("neither ASCII (no 'solid') nor binary (under 84 bytes)");
  return bad("binary: the header promises " + str(count) + " triangles (" +
             str(static_cast<long long>(kStlHeader + kStlTriangle * std::uint64_t{count})) +
             " bytes), the file has " + str(static_cast<long long>(size)) + " bytes");
}

// ---------------------------------------------------------------- OBJ

/// The vertex of a face corner "v", "v/t", "v//n" or "v/t/n", as an absolute
/// 0-based index (negative ones count back from the last vertex read).
bool objCorner(std::string_view token, long long defined, long long& out) {
  long long id = 0;
  if (!parseInteger(token.substr(0, token.find('/')), id) || id == 0) return false;
  out = id > 0 ? id - 1 : defined + id;
  return true;
}

/// One line of an OBJ file; the triangles' corners go to `face_ids` (with the line
/// number, four values a triangle), checked once every vertex is known.
sc::Status readObjLine(const std::vector<std::string_view>& t, long long line,
                       std::vector<long long>& corners, std::vector<long long>& face_ids,
                       Polygons& out) {
  const std::string what = "line " + str(line);
  if (t[0] == "v") {
    if (t.size() < 4 || t.size() > 8) return bad(what + ": a vertex needs 3 coordinates");
    for (std::size_t k = 4; k < t.size(); ++k) {
      double extra = 0;
      if (!parseReal(t[k], extra)) return bad(what + ": " + quoted(t[k]) + " is not a number");
    }
    return readPosition(t, 1, what + ": the vertex", out);
  }
  if (t[0] == "l" || t[0] == "p") {
    ++out.skipped;
    return sc::Status::success();
  }
  if (t[0] != "f") return sc::Status::success();  // normals, texture, groups, materials
  if (t.size() < 4) return bad(what + ": a face needs 3 corners");
  corners.resize(t.size() - 1);
  const auto defined = static_cast<long long>(out.positions.size());
  for (std::size_t k = 1; k < t.size(); ++k)
    if (!objCorner(t[k], defined, corners[k - 1]) || corners[k - 1] < 0)
      return bad(what + ": " + quoted(t[k]) + " is not a vertex reference");
  for (std::size_t k = 1; k + 1 < corners.size(); ++k)
    face_ids.insert(face_ids.end(), {corners[0], corners[k], corners[k + 1], line});
  return sc::Status::success();
}

sc::Status readObj(const char* data, std::size_t size, Polygons& out) {
  Lines lines(data, size);
  std::vector<std::string_view> tokens;
  std::vector<long long> corners, face_ids;
  for (long long line = 1; !lines.done(); ++line) {
    split(lines.next(), tokens, true);
    if (tokens.empty()) continue;
    if (sc::Status s = readObjLine(tokens, line, corners, face_ids, out); !s.ok()) return s;
  }
  const auto count = static_cast<long long>(out.positions.size());
  std::vector<long long> corner_ids(3);
  for (std::size_t f = 0; 4 * f < face_ids.size(); ++f) {
    const long long* ids = &face_ids[4 * f];
    corner_ids.assign(ids, ids + 3);
    if (sc::Status s = addPolygon(corner_ids, count, "the face on line " + str(ids[3]), out, 1);
        !s.ok())
      return s;
  }
  return sc::Status::success();
}

// ---------------------------------------------------------------- common

/// Equal positions become one vertex; unreferenced positions are dropped.
ImportedMesh weld(const Polygons& in) {
  ImportedMesh out;
  out.skipped = in.skipped;
  std::map<Position, int> welded;
  std::vector<int> index(in.positions.size(), -1);
  for (const sc::Tri& t : in.triangles) {
    sc::Tri tri;
    for (int k = 0; k < 3; ++k) {
      int& id = index[static_cast<std::size_t>(t[k])];
      if (id < 0) {
        const Position& p = in.positions[static_cast<std::size_t>(t[k])];
        const auto [it, inserted] = welded.emplace(p, static_cast<int>(out.mesh.vertices.size()));
        if (inserted) out.mesh.vertices.emplace_back(p[0], p[1], p[2]);
        id = it->second;
      }
      tri[k] = id;
    }
    out.mesh.triangles.push_back(tri);
  }
  return out;
}

}  // namespace

bool hasStrictReader(const std::string& extension) {
  return extension == "off" || extension == "ply" || extension == "stl" || extension == "obj";
}

sc::Result<ImportedMesh> parseStrict(const char* data, std::size_t size,
                                     const std::string& extension, const std::string& source) {
  Polygons polygons;
  sc::Status s = extension == "off"   ? readOff(data, size, polygons)
                 : extension == "ply" ? readPly(data, size, polygons)
                 : extension == "stl" ? readStl(data, size, polygons)
                 : extension == "obj" ? readObj(data, size, polygons)
                                      : bad("no reader for this format");
  std::string format = extension;
  for (char& c : format) c = static_cast<char>(c - 'a' + 'A');
  if (!s.ok()) return bad("'" + source + "': " + format + ": " + s.message());
  if (polygons.triangles.empty()) return bad("'" + source + "' has no triangles");
  return weld(polygons);
}

}  // namespace sc::tools
