#include "base/graph/vtp_polylines.hpp"

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <pugixml.hpp>
#include <sstream>
#include <stdexcept>

namespace gw {
namespace {

// Thrown inside; read_vtp_polylines prefixes the path.
struct VtpError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Encoding {
  bool big_endian = false;
  int header_bytes = 4;  // header_type UInt32 (the default before VTK file version 1.0) or UInt64
  bool zlib = false;
};

// Bytes of one array's data in order, from wherever the format keeps them.
class ByteSource {
 public:
  virtual ~ByteSource() = default;
  // The next n bytes; throws naming `what` when the data ends first.
  virtual std::string take(size_t n, const std::string& what) = 0;
};

class RawSource : public ByteSource {
 public:
  RawSource(const char* begin, const char* end) : at_(begin), end_(end) {}
  std::string take(size_t n, const std::string& what) override {
    if (static_cast<size_t>(end_ - at_) < n)
      throw VtpError(what + ": the file ends before its data does (truncated: " + std::to_string(n) +
                     " bytes wanted, " + std::to_string(end_ - at_) + " left)");
    std::string out(at_, n);
    at_ += n;
    return out;
  }

 private:
  const char* at_;
  const char* end_;
};

// Base64, decoded one 4-character group at a time. A padded group ends one encoded block and the
// next group starts a new one: VTK encodes an array's header and its data as separate blocks.
class Base64Source : public ByteSource {
 public:
  Base64Source(const char* begin, const char* end) : at_(begin), end_(end) {}
  std::string take(size_t n, const std::string& what) override {
    while (buffer_.size() - used_ < n) {
      if (!decode_group(what))
        throw VtpError(what + ": the base64 text ends before its data does (truncated: " + std::to_string(n) +
                       " bytes wanted)");
    }
    std::string out = buffer_.substr(used_, n);
    used_ += n;
    if (used_ > 4096) {
      buffer_.erase(0, used_);
      used_ = 0;
    }
    return out;
  }

 private:
  static int value(char c) {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
  }
  static bool space(char c) { return c == ' ' || c == '\n' || c == '\r' || c == '\t'; }

  // Appends the next group's 1-3 bytes; false at the end of the text.
  bool decode_group(const std::string& what) {
    char group[4];
    int have = 0;
    while (have < 4 && at_ < end_) {
      const char c = *at_++;
      if (space(c)) continue;
      if (c != '=' && value(c) < 0) {
        std::ostringstream s;
        s << what << ": bad base64: character ";
        if (c >= 33 && c < 127) s << "'" << c << "'";
        else s << "code " << static_cast<int>(static_cast<unsigned char>(c));
        s << " is not base64";
        throw VtpError(s.str());
      }
      group[have++] = c;
    }
    if (have == 0) return false;
    if (have < 4) throw VtpError(what + ": bad base64: the text ends inside a 4-character group (truncated)");
    const int pad = (group[3] == '=') + (group[2] == '=');
    if (group[0] == '=' || group[1] == '=' || (group[2] == '=' && group[3] != '='))
      throw VtpError(what + ": bad base64: misplaced '=' padding");
    const unsigned v = (static_cast<unsigned>(value(group[0])) << 18) | (static_cast<unsigned>(value(group[1])) << 12) |
                       (pad < 2 ? static_cast<unsigned>(value(group[2])) << 6 : 0u) |
                       (pad < 1 ? static_cast<unsigned>(value(group[3])) : 0u);
    buffer_.push_back(static_cast<char>((v >> 16) & 0xff));
    if (pad < 2) buffer_.push_back(static_cast<char>((v >> 8) & 0xff));
    if (pad < 1) buffer_.push_back(static_cast<char>(v & 0xff));
    return true;
  }

  const char* at_;
  const char* end_;
  std::string buffer_;
  size_t used_ = 0;
};

std::uint64_t unsigned_value(const std::string& bytes, bool big_endian) {
  std::uint64_t v = 0;
  for (size_t i = 0; i < bytes.size(); ++i) {
    const auto b = static_cast<std::uint64_t>(static_cast<unsigned char>(bytes[big_endian ? i : bytes.size() - 1 - i]));
    v = (v << 8) | b;
  }
  return v;
}

// One array's (uncompressed) bytes: a size header and the data, or vtkZLibDataCompressor's
// header [blocks, block size, last block size, compressed size of each block] and the blocks.
std::string read_block(ByteSource& src, const Encoding& e, const std::string& what) {
  auto header_value = [&]() { return unsigned_value(src.take(static_cast<size_t>(e.header_bytes), what), e.big_endian); };
  constexpr std::uint64_t kMaxBytes = std::uint64_t{1} << 34;  // 16 GiB: more is a corrupt header
  if (!e.zlib) {
    const std::uint64_t size = header_value();
    if (size > kMaxBytes) throw VtpError(what + ": corrupt data header (claims " + std::to_string(size) + " bytes)");
    return src.take(static_cast<size_t>(size), what);
  }
  const std::uint64_t blocks = header_value();
  const std::uint64_t block_size = header_value();
  const std::uint64_t last_size = header_value();
  if (blocks > (kMaxBytes >> 10) || block_size > kMaxBytes || last_size > block_size ||
      (blocks > 0 && block_size == 0) || blocks * block_size > kMaxBytes)
    throw VtpError(what + ": corrupt compression header (" + std::to_string(blocks) + " blocks of " +
                   std::to_string(block_size) + " bytes, last " + std::to_string(last_size) + ")");
  std::vector<std::uint64_t> compressed(blocks);
  for (auto& c : compressed) {
    c = header_value();
    if (c > kMaxBytes) throw VtpError(what + ": corrupt compression header (a block of " + std::to_string(c) + " bytes)");
  }
  std::string out;
  for (std::uint64_t b = 0; b < blocks; ++b) {
    const std::string packed = src.take(static_cast<size_t>(compressed[b]), what);
    const std::uint64_t expected = (b + 1 == blocks && last_size != 0) ? last_size : block_size;
    std::string unpacked(static_cast<size_t>(expected), '\0');
    uLongf length = static_cast<uLongf>(expected);
    const int rc = uncompress(reinterpret_cast<Bytef*>(unpacked.data()), &length,
                              reinterpret_cast<const Bytef*>(packed.data()), static_cast<uLong>(packed.size()));
    if (rc != Z_OK || length != expected) {
      std::string why = rc == Z_DATA_ERROR  ? "corrupt or truncated stream"
                        : rc == Z_BUF_ERROR ? "truncated stream or more data than the header says"
                        : rc == Z_MEM_ERROR ? "out of memory"
                        : rc == Z_OK        ? std::to_string(length) + " bytes instead of " + std::to_string(expected)
                                            : "error " + std::to_string(rc);
      throw VtpError(what + ": zlib data of block " + std::to_string(b + 1) + " of " + std::to_string(blocks) +
                     " cannot be inflated (" + why + ")");
    }
    out += unpacked;
  }
  return out;
}

struct TypeInfo {
  int bytes = 0;
  bool is_float = false;
  bool is_signed = false;
};

TypeInfo type_info(const std::string& type, const std::string& what) {
  static const std::map<std::string, TypeInfo> types = {
      {"Int8", {1, false, true}},    {"UInt8", {1, false, false}},  {"Int16", {2, false, true}},
      {"UInt16", {2, false, false}}, {"Int32", {4, false, true}},   {"UInt32", {4, false, false}},
      {"Int64", {8, false, true}},   {"UInt64", {8, false, false}}, {"Float32", {4, true, true}},
      {"Float64", {8, true, true}}};
  const auto it = types.find(type);
  if (it == types.end())
    throw VtpError(what + ": has type '" + type + "', not a number type (Float32, Float64, Int8..Int64, UInt8..UInt64)");
  return it->second;
}

std::vector<double> bytes_to_values(const std::string& bytes, const TypeInfo& t, bool big_endian, const std::string& what) {
  if (bytes.size() % static_cast<size_t>(t.bytes) != 0)
    throw VtpError(what + ": " + std::to_string(bytes.size()) + " bytes is not a whole number of " +
                   std::to_string(t.bytes) + "-byte values");
  std::vector<double> out(bytes.size() / static_cast<size_t>(t.bytes));
  char v[8] = {};
  const size_t width = std::min<size_t>(static_cast<size_t>(t.bytes), sizeof v);
  for (size_t i = 0; i < out.size(); ++i) {
    const char* src = bytes.data() + i * static_cast<size_t>(t.bytes);
    for (size_t k = 0; k < width; ++k)  // the file's byte order to this (little-endian) machine's
      v[k] = src[big_endian ? width - 1 - k : k];
    switch (t.bytes * (t.is_float ? 10 : 1) * (t.is_signed ? 1 : -1)) {
      case 1: out[i] = static_cast<std::int8_t>(v[0]); break;
      case -1: out[i] = static_cast<std::uint8_t>(v[0]); break;
      case 2: { std::int16_t x; std::memcpy(&x, v, 2); out[i] = x; break; }
      case -2: { std::uint16_t x; std::memcpy(&x, v, 2); out[i] = x; break; }
      case 4: { std::int32_t x; std::memcpy(&x, v, 4); out[i] = x; break; }
      case -4: { std::uint32_t x; std::memcpy(&x, v, 4); out[i] = x; break; }
      case 8: { std::int64_t x; std::memcpy(&x, v, 8); out[i] = static_cast<double>(x); break; }
      case -8: { std::uint64_t x; std::memcpy(&x, v, 8); out[i] = static_cast<double>(x); break; }
      case 40: { float x; std::memcpy(&x, v, 4); out[i] = x; break; }
      case 80: { double x; std::memcpy(&x, v, 8); out[i] = x; break; }
      default: throw VtpError(what + ": unsupported value type");
    }
  }
  return out;
}

struct Document {
  std::string path;
  std::string data;              // the whole file
  Encoding encoding;
  const char* appended = nullptr;  // first byte after '_' of <AppendedData>, or null
  const char* appended_end = nullptr;
  bool appended_base64 = false;
};

std::string array_label(const pugi::xml_node& a, const std::string& where) {
  const std::string name = a.attribute("Name").as_string();
  return where + " array '" + (name.empty() ? std::string("(unnamed)") : name) + "'";
}

// The bytes of a binary or appended DataArray (not ascii).
std::string binary_bytes(const Document& doc, const pugi::xml_node& a, const std::string& what) {
  const std::string format = a.attribute("format").as_string("ascii");
  if (format == "binary") {
    const char* text = a.child_value();
    Base64Source src(text, text + std::strlen(text));
    return read_block(src, doc.encoding, what);
  }
  if (format == "appended") {
    if (!doc.appended) throw VtpError(what + ": format 'appended' but the file has no <AppendedData> section");
    const pugi::xml_attribute off = a.attribute("offset");
    if (!off) throw VtpError(what + ": format 'appended' without an offset");
    const long long offset = off.as_llong(-1);
    if (offset < 0 || offset > doc.appended_end - doc.appended)
      throw VtpError(what + ": offset " + std::string(off.value()) + " is outside the appended data (" +
                     std::to_string(doc.appended_end - doc.appended) + " bytes; file truncated?)");
    if (doc.appended_base64) {
      Base64Source src(doc.appended + offset, doc.appended_end);
      return read_block(src, doc.encoding, what);
    }
    RawSource src(doc.appended + offset, doc.appended_end);
    return read_block(src, doc.encoding, what);
  }
  throw VtpError(what + ": unknown format '" + format + "' (ascii, binary or appended)");
}

std::vector<double> ascii_values(const pugi::xml_node& a, const std::string& what) {
  std::vector<double> out;
  const char* p = a.child_value();
  while (true) {
    while (*p == ' ' || *p == '\n' || *p == '\r' || *p == '\t') ++p;
    if (!*p) break;
    char* end = nullptr;
    const double v = std::strtod(p, &end);
    if (end == p) {
      std::string token;
      for (const char* q = p; *q && !std::isspace(static_cast<unsigned char>(*q)) && token.size() < 20; ++q) token += *q;
      throw VtpError(what + ": '" + token + "' is not a number");
    }
    out.push_back(v);
    p = end;
  }
  return out;
}

std::vector<double> array_values(const Document& doc, const pugi::xml_node& a, const std::string& what) {
  const TypeInfo t = type_info(a.attribute("type").as_string(), what);
  if (std::string(a.attribute("format").as_string("ascii")) == "ascii") return ascii_values(a, what);
  return bytes_to_values(binary_bytes(doc, a, what), t, doc.encoding.big_endian, what);
}

// A field-data string array: VTK writes strings as their bytes, each ended by a NUL (ascii: codes).
std::string string_array(const Document& doc, const pugi::xml_node& a, const std::string& what) {
  std::string out;
  if (std::string(a.attribute("format").as_string("ascii")) == "ascii") {
    for (double c : ascii_values(a, what)) out.push_back(static_cast<char>(static_cast<int>(c)));
  } else {
    out = binary_bytes(doc, a, what);
  }
  return out.substr(0, out.find('\0'));
}

// <DataArray>, or <Array> (how VTK writes string arrays, e.g. Slicer's field data "SPACE").
pugi::xml_node named_array(const pugi::xml_node& parent, const std::string& name) {
  for (pugi::xml_node a : parent.children())
    if ((std::string(a.name()) == "DataArray" || std::string(a.name()) == "Array") && name == a.attribute("Name").as_string())
      return a;
  return {};
}

std::string array_names(const pugi::xml_node& parent) {
  std::string names;
  for (pugi::xml_node a : parent.children("DataArray"))
    names += (names.empty() ? "" : ", ") + std::string(a.attribute("Name").as_string("(unnamed)"));
  return names.empty() ? "none" : names;
}

size_t count_attribute(const pugi::xml_node& piece, const char* name) {
  const pugi::xml_attribute a = piece.attribute(name);
  if (!a) return 0;
  const long long n = a.as_llong(-1);
  if (n < 0 || std::string(a.value()).find_first_not_of("0123456789") != std::string::npos)
    throw VtpError(std::string("Piece ") + name + " '" + a.value() + "' is not a count");
  return static_cast<size_t>(n);
}

// Splits the file into the XML header (parsed) and the appended data (kept as bytes: raw
// appended data is binary and not XML).
void parse_document(Document& doc, pugi::xml_document& xml) {
  std::string text = doc.data;
  const size_t tag = doc.data.find("<AppendedData");
  if (tag != std::string::npos) {
    const size_t close = doc.data.find('>', tag);
    const size_t underscore = close == std::string::npos ? close : doc.data.find('_', close);
    if (underscore == std::string::npos)
      throw VtpError("<AppendedData> has no '_' before its data (truncated file?)");
    size_t end = doc.data.rfind("</AppendedData>");
    if (end == std::string::npos || end < underscore) end = doc.data.size();  // truncated: reads will say so
    doc.appended = doc.data.data() + underscore + 1;
    doc.appended_end = doc.data.data() + end;
    text = doc.data.substr(0, close + 1) + "</AppendedData></VTKFile>";
  }
  const pugi::xml_parse_result ok = xml.load_buffer(text.data(), text.size());
  if (!ok)
    throw VtpError(std::string("not a readable VTK XML file (XML: ") + ok.description() + " at byte " +
                   std::to_string(ok.offset) + ")");
  if (tag != std::string::npos) {
    const std::string enc = xml.child("VTKFile").child("AppendedData").attribute("encoding").as_string("raw");
    if (enc != "raw" && enc != "base64") throw VtpError("<AppendedData> encoding '" + enc + "' (raw or base64)");
    doc.appended_base64 = enc == "base64";
  }
}

// The whole file's bytes.
std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw VtpError("cannot open file");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// <VTKFile>'s attributes: anything but PolyData is refused; its byte order, header type and
// compressor go to doc.encoding.
void read_encoding(const pugi::xml_node& root, Document& doc) {
  const std::string type = root.attribute("type").as_string();
  if (type != "PolyData") throw VtpError("a VTK '" + type + "' file, not PolyData");
  const std::string order = root.attribute("byte_order").as_string("LittleEndian");
  if (order != "LittleEndian" && order != "BigEndian") throw VtpError("unknown byte_order '" + order + "'");
  doc.encoding.big_endian = order == "BigEndian";
  const std::string header = root.attribute("header_type").as_string("UInt32");
  if (header != "UInt32" && header != "UInt64") throw VtpError("header_type '" + header + "' (UInt32 or UInt64)");
  doc.encoding.header_bytes = header == "UInt64" ? 8 : 4;
  const std::string compressor = root.attribute("compressor").as_string();
  if (!compressor.empty() && compressor != "vtkZLibDataCompressor")
    throw VtpError("compressor '" + compressor + "' is not supported (vtkZLibDataCompressor or none)");
  doc.encoding.zlib = !compressor.empty();
}

// out.space from <PolyData>'s field data "SPACE" (Slicer's): LPS, RAS, or "" for neither.
void read_space(const Document& doc, const pugi::xml_node& poly, VtpPolylines& out) {
  if (const pugi::xml_node space = named_array(poly.child("FieldData"), "SPACE")) {
    const std::string s = string_array(doc, space, array_label(space, "field data"));
    out.space = s.find("LPS") != std::string::npos ? "LPS" : s.find("RAS") != std::string::npos ? "RAS" : "";
  }
}

// A piece's n (> 0) points, appended to out.points; `where` prefixes messages.
void read_piece_points(const Document& doc, const pugi::xml_node& piece, size_t n, const std::string& where,
                       VtpPolylines& out) {
  const pugi::xml_node pa = piece.child("Points").child("DataArray");
  if (!pa) throw VtpError(where + "NumberOfPoints is " + std::to_string(n) + " but there is no <Points> array");
  const std::string what = where + "array 'Points'";
  if (pa.attribute("NumberOfComponents").as_int(1) != 3)
    throw VtpError(what + ": " + std::string(pa.attribute("NumberOfComponents").as_string("1")) +
                   " components, not 3");
  const std::vector<double> xyz = array_values(doc, pa, what);
  if (xyz.size() != 3 * n)
    throw VtpError(what + ": " + std::to_string(xyz.size()) + " values for " + std::to_string(n) +
                   " points (truncated?)");
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d p(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
    if (!p.allFinite()) throw VtpError(what + ": point " + std::to_string(i) + " is not finite");
    out.points.push_back(p);
  }
}

// A piece's `wanted` point arrays (n values each), appended to out.point_arrays.
void read_piece_arrays(const Document& doc, const pugi::xml_node& piece, size_t n, const std::string& where,
                       const std::vector<std::string>& wanted, VtpPolylines& out) {
  const pugi::xml_node pd = piece.child("PointData");
  for (const std::string& name : wanted) {
    const pugi::xml_node a = named_array(pd, name);
    if (!a)
      throw VtpError(where + "point array '" + name + "' is missing (point arrays here: " + array_names(pd) + ")");
    const std::string what = where + array_label(a, "point");
    if (a.attribute("NumberOfComponents").as_int(1) != 1)
      throw VtpError(what + ": " + std::string(a.attribute("NumberOfComponents").value()) + " components, not 1");
    const std::vector<double> v = array_values(doc, a, what);
    if (v.size() != n)
      throw VtpError(what + ": " + std::to_string(v.size()) + " values for " + std::to_string(n) + " points");
    auto& dst = out.point_arrays[name];
    dst.insert(dst.end(), v.begin(), v.end());
  }
}

// A piece's polyline cells, appended to out.lines as ids into out.points (the piece's n points
// start at first_point).
void read_piece_lines(const Document& doc, const pugi::xml_node& piece, size_t n, size_t first_point,
                      const std::string& where, VtpPolylines& out) {
  const size_t lines = count_attribute(piece, "NumberOfLines");
  if (lines == 0) return;
  const pugi::xml_node la = piece.child("Lines");
  const pugi::xml_node ca = named_array(la, "connectivity");
  const pugi::xml_node oa = named_array(la, "offsets");
  if (!ca || !oa)
    throw VtpError(where + "NumberOfLines is " + std::to_string(lines) +
                   " but <Lines> lacks its 'connectivity' or 'offsets' array (has: " + array_names(la) + ")");
  const std::vector<double> conn = array_values(doc, ca, where + "lines array 'connectivity'");
  std::vector<double> offsets = array_values(doc, oa, where + "lines array 'offsets'");
  // VTK writes one end offset per cell; a leading 0 (the in-memory layout) is accepted too.
  if (offsets.size() == lines + 1 && offsets.front() == 0.0) offsets.erase(offsets.begin());
  if (offsets.size() != lines)
    throw VtpError(where + "lines array 'offsets': " + std::to_string(offsets.size()) + " values for " +
                   std::to_string(lines) + " lines");
  double begin = 0;
  for (size_t c = 0; c < lines; ++c) {
    const double end = offsets[c];
    if (!(end >= begin && end <= static_cast<double>(conn.size())) || end != std::floor(end))
      throw VtpError(where + "lines array 'offsets': offset " + std::to_string(end) + " of line " +
                     std::to_string(c) + " is out of order or past the " + std::to_string(conn.size()) +
                     " connectivity entries");
    std::vector<std::int64_t> ids;
    for (auto i = static_cast<size_t>(begin); i < static_cast<size_t>(end); ++i) {
      const double id = conn[i];
      if (!(id >= 0 && id < static_cast<double>(n)) || id != std::floor(id))
        throw VtpError(where + "lines array 'connectivity': point id " + std::to_string(id) + " of line " +
                       std::to_string(c) + " is not one of the " + std::to_string(n) + " points");
      ids.push_back(static_cast<std::int64_t>(first_point) + static_cast<std::int64_t>(id));
    }
    out.lines.push_back(std::move(ids));
    begin = end;
  }
}

// One <Piece>: its points, its `wanted` point arrays and its lines, appended to `out`.
void read_piece(const Document& doc, const pugi::xml_node& piece, const std::string& where,
                const std::vector<std::string>& wanted, VtpPolylines& out) {
  const size_t n = count_attribute(piece, "NumberOfPoints");
  const size_t first_point = out.points.size();
  if (n > 0) read_piece_points(doc, piece, n, where, out);
  read_piece_arrays(doc, piece, n, where, wanted, out);
  read_piece_lines(doc, piece, n, first_point, where, out);
}

}  // namespace

VtpPolylines read_vtp_polylines(const std::string& path, const std::vector<std::string>& wanted) {
  try {
    Document doc;
    doc.path = path;
    doc.data = read_file(path);
    if (doc.data.empty()) throw VtpError("empty file");
    pugi::xml_document xml;
    parse_document(doc, xml);
    const pugi::xml_node root = xml.child("VTKFile");
    if (!root) throw VtpError("not a VTK XML file (no <VTKFile> element)");
    read_encoding(root, doc);

    const pugi::xml_node poly = root.child("PolyData");
    if (!poly || !poly.child("Piece")) throw VtpError("no <PolyData><Piece> element");
    VtpPolylines out;
    for (const std::string& name : wanted) out.point_arrays[name];
    read_space(doc, poly, out);

    int piece_index = 0;
    for (pugi::xml_node piece : poly.children("Piece")) {
      const std::string where = poly.select_nodes("Piece").size() > 1 ? "piece " + std::to_string(piece_index) + ": " : "";
      ++piece_index;
      read_piece(doc, piece, where, wanted, out);
    }
    if (out.lines.empty()) throw VtpError("no lines (polyline cells): not a centerline file?");
    return out;
  } catch (const VtpError& e) {
    throw std::runtime_error(path + ": " + e.what());
  } catch (const std::bad_alloc&) {
    throw std::runtime_error(path + ": out of memory reading the file (corrupt sizes?)");
  }
}

}  // namespace gw
