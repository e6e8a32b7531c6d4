#include "telear/geometry/mesh_file_check.hpp"

#include <tinyxml.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>
#include <utility>
#include <vector>

#include "telear/core/utf8.hpp"

namespace telear::geometry {
namespace {

constexpr std::string_view kPrimitives[] = {"triangles",  "polylist",  "polygons", "lines",
                                            "linestrips", "tristrips", "trifans"};

bool is_primitive(std::string_view name) {
  for (std::string_view p : kPrimitives) {
    if (name == p) return true;
  }
  return false;
}

void collect_ids(const TiXmlElement* e, std::set<std::string>& ids) {
  for (; e != nullptr; e = e->NextSiblingElement()) {
    if (const char* id = e->Attribute("id")) ids.insert(id);
    collect_ids(e->FirstChildElement(), ids);
  }
}

bool has_input(const TiXmlElement* e, std::string_view semantic) {
  for (const TiXmlElement* i = e->FirstChildElement("input"); i != nullptr;
       i = i->NextSiblingElement("input")) {
    const char* s = i->Attribute("semantic");
    if (s != nullptr && semantic == s) return true;
  }
  return false;
}

class Checker {
 public:
  explicit Checker(std::set<std::string> ids) : ids_(std::move(ids)) {}

  // The first problem found in `e` and below, or empty.
  std::string check(const TiXmlElement* e, bool in_mesh) const {
    for (; e != nullptr; e = e->NextSiblingElement()) {
      const std::string_view name = e->Value();
      if (std::string problem = check_one(*e, name, in_mesh); !problem.empty()) return problem;
      if (std::string problem = check(e->FirstChildElement(), in_mesh || name == "mesh");
          !problem.empty()) {
        return problem;
      }
    }
    return {};
  }

 private:
  std::string check_one(const TiXmlElement& e, std::string_view name, bool in_mesh) const {
    const std::string where = "<" + std::string(name) + "> on line " + std::to_string(e.Row());
    if (name == "input") {
      if (e.Attribute("semantic") == nullptr) return where + " has no semantic";
      if (std::string problem = reference(e, "source", where); !problem.empty()) return problem;
    } else if (name == "vertices") {
      if (!has_input(&e, "POSITION")) return where + " has no POSITION input";
    } else if (name == "accessor") {
      if (std::string problem = reference(e, "source", where); !problem.empty()) return problem;
    } else if (name.rfind("instance_", 0) == 0) {
      // Required by COLLADA's schema: assimp threw on an <instance_geometry> without its url
      // and leaked the scene (fuzz/crashes/mesh/collada_instance_without_url.dae).
      const char* attribute = name == "instance_material" ? "target" : "url";
      if (std::string problem = reference(e, attribute, where); !problem.empty()) return problem;
    } else if (name == "float_array") {
      return check_float_array(e, where);
    } else if (const int n = fixed_count(name); n > 0) {
      // assimp reads these numbers word by word and throws on a word that is not one, leaking
      // the scene it was building (a node's <scale>[2 2 2</scale>: fuzz/crashes/mesh/).
      const auto values = numbers(&e, false);
      const bool rgb = name == "color" && values && values->size() == 3;
      if (!values || (values->size() != static_cast<std::size_t>(n) && !rgb)) {
        return where + " does not hold " + std::to_string(n) + " numbers";
      }
    } else if (in_mesh && is_primitive(name)) {
      if (!has_input(&e, "VERTEX")) return where + " has no VERTEX input";
      if (e.FirstChildElement("p") == nullptr) return where + " has no index list <p>";
      if (name == "polylist" && e.FirstChildElement("vcount") == nullptr) {
        return where + " has no <vcount>";
      }
      return check_indices(e, name, where);
    }
    return {};
  }

  // How many numbers a node transform, a colour (RGBA; RGB also) or a float holds; 0 for any
  // other element.
  static int fixed_count(std::string_view name) {
    static constexpr std::pair<std::string_view, int> kCounts[] = {
        {"translate", 3}, {"scale", 3}, {"rotate", 4}, {"matrix", 16},
        {"lookat", 9},    {"skew", 7},  {"color", 4},  {"float", 1}};
    for (const auto& [element, count] : kCounts) {
      if (name == element) return count;
    }
    return 0;
  }

  // The numbers in an element's text, or nullopt when a word is not one (integers: digits).
  static std::optional<std::vector<double>> numbers(const TiXmlElement* e, bool integers) {
    std::vector<double> values;
    std::istringstream words(e->GetText() != nullptr ? e->GetText() : "");
    std::string word;
    while (words >> word) {
      if (integers && word.find_first_not_of("0123456789") != std::string::npos) {
        return std::nullopt;
      }
      char* end = nullptr;
      const double v = std::strtod(word.c_str(), &end);
      if (end == word.c_str() || *end != '\0') return std::nullopt;
      values.push_back(v);
    }
    return values;
  }

  static std::string check_float_array(const TiXmlElement& e, const std::string& where) {
    const auto values = numbers(&e, false);
    if (!values) return where + " holds a word that is not a number";
    int count = -1;
    if (e.QueryIntAttribute("count", &count) != TIXML_SUCCESS || count < 0 ||
        static_cast<std::size_t>(count) != values->size()) {
      return where + ": count " + (e.Attribute("count") ? e.Attribute("count") : "(none)") +
             " but " + std::to_string(values->size()) + " values";
    }
    return {};
  }

  // The index list's length against the primitive's count (assimp reads `count` primitives and
  // spends minutes and gigabytes on a list shorter than it says: another fuzzer finding).
  static std::string check_indices(const TiXmlElement& e, std::string_view name,
                                   const std::string& where) {
    int max_offset = 0;
    for (const TiXmlElement* i = e.FirstChildElement("input"); i != nullptr;
         i = i->NextSiblingElement("input")) {
      int offset = 0;
      if (i->QueryIntAttribute("offset", &offset) == TIXML_SUCCESS) {
        if (offset < 0 || offset > 64) return where + ": an input offset outside 0..64";
        max_offset = std::max(max_offset, offset);
      }
    }
    const std::size_t stride = static_cast<std::size_t>(max_offset) + 1;
    std::size_t indices = 0;
    for (const TiXmlElement* p = e.FirstChildElement("p"); p != nullptr;
         p = p->NextSiblingElement("p")) {
      const auto list = numbers(p, true);
      if (!list) return where + " has a <p> that is not a list of indices";
      indices += list->size();
    }
    int count = -1;
    if (e.QueryIntAttribute("count", &count) != TIXML_SUCCESS || count < 0) {
      return where + " has no count";
    }
    std::size_t corners = 0;  // vertices the primitives need
    if (name == "triangles") {
      corners = 3 * static_cast<std::size_t>(count);
    } else if (name == "lines") {
      corners = 2 * static_cast<std::size_t>(count);
    } else if (name == "polylist") {
      const auto vcount = numbers(e.FirstChildElement("vcount"), true);
      if (!vcount || vcount->size() != static_cast<std::size_t>(count)) {
        return where + ": <vcount> does not hold count = " + std::to_string(count) + " sizes";
      }
      for (double v : *vcount) corners += static_cast<std::size_t>(v);
    } else {
      return {};  // strips, fans, polygons: one <p> per primitive, any length
    }
    if (indices != corners * stride) {
      return where + ": count " + std::to_string(count) + " needs " +
             std::to_string(corners * stride) + " indices, <p> holds " + std::to_string(indices);
    }
    return {};
  }

  // An attribute "#id" that names an element of the file.
  std::string reference(const TiXmlElement& e, const char* attribute,
                        const std::string& where) const {
    const char* value = e.Attribute(attribute);
    if (value == nullptr) return where + " has no " + attribute;
    const std::string_view v(value);
    if (v.size() < 2 || v.front() != '#') {
      return where + ": " + attribute + " '" + std::string(v) + "' is not a '#id' of this file";
    }
    if (ids_.count(std::string(v.substr(1))) == 0) {
      return where + ": " + attribute + " '" + std::string(v) + "' names no element of the file";
    }
    return {};
  }

  std::set<std::string> ids_;
};

}  // namespace

Status check_collada_structure(const std::string& text, const std::string& path) {
  // TinyXML 1 read past the text on a multi-byte character cut by its end (a heap overflow:
  // fuzz/crashes/mesh/collada_utf8_cut_at_the_end.dae), as on the URDF door: XML is UTF-8.
  if (const auto bad = core::first_invalid_utf8(text)) {
    return Error{"mesh file " + path +
                 " is not a readable mesh (COLLADA: not UTF-8 text, an invalid byte sequence at "
                 "byte " +
                 std::to_string(*bad) + ")"};
  }
  TiXmlDocument doc;
  doc.Parse(text.c_str());
  if (doc.Error()) {
    return Error{"mesh file " + path + " is not a readable mesh (COLLADA: not well-formed XML: " +
                 doc.ErrorDesc() + " on line " + std::to_string(doc.ErrorRow()) + ")"};
  }
  const TiXmlElement* root = doc.RootElement();
  if (root == nullptr || std::string_view(root->Value()) != "COLLADA") {
    return Error{"mesh file " + path +
                 " is not a readable mesh (COLLADA: the root element is not <COLLADA>)"};
  }
  std::set<std::string> ids;
  collect_ids(root, ids);
  if (std::string problem = Checker(std::move(ids)).check(root->FirstChildElement(), false);
      !problem.empty()) {
    return Error{"mesh file " + path + " is not a readable mesh (COLLADA: " + problem + ")"};
  }
  return Status::Ok();
}

namespace {

// assimp's text readers stop at a NUL byte as at the file's end, and take only spaces and tabs
// between words: a file cut short inside a statement, or a word it cannot read (a vertical tab
// before a number, which the checks below, reading words as C++ streams do, take for a space),
// and they leak what they were building (an ASCII STL's facet, an OBJ's mesh:
// fuzz/crashes/mesh/). A text format has no control character but tab, CR and LF.
std::optional<Error> control_character_error(const std::string& text, const std::string& path,
                                             const char* format) {
  const auto bad = std::find_if(text.begin(), text.end(), [](char c) {
    const auto u = static_cast<unsigned char>(c);
    return (u < 0x20 && c != '\t' && c != '\r' && c != '\n') || u == 0x7f;
  });
  if (bad == text.end()) return std::nullopt;
  const auto line = std::count(text.begin(), bad, '\n');
  char code[8];
  std::snprintf(code, sizeof code, "0x%02X", static_cast<unsigned char>(*bad));
  const std::string what =
      *bad == '\0' ? std::string("a NUL byte") : std::string("a control character (") + code + ")";
  return Error{"mesh file " + path + " is not a readable mesh (" + format + ", line " +
               std::to_string(line + 1) + ": " + what + " in the text)"};
}

// A number as assimp's readers take it: [+-]digits[.digits][(e|E)[+-]digits], or .digits.
bool is_decimal_number(const std::string& word) {
  std::size_t i = 0;
  const auto digits = [&] {
    const std::size_t start = i;
    while (i < word.size() && std::isdigit(static_cast<unsigned char>(word[i]))) ++i;
    return i - start;
  };
  if (i < word.size() && (word[i] == '+' || word[i] == '-')) ++i;
  std::size_t mantissa = digits();
  if (i < word.size() && word[i] == '.') {
    ++i;
    mantissa += digits();
  }
  if (mantissa == 0) return false;
  if (i < word.size() && (word[i] == 'e' || word[i] == 'E')) {
    ++i;
    if (i < word.size() && (word[i] == '+' || word[i] == '-')) ++i;
    if (digits() == 0) return false;
  }
  return i == word.size();
}

// An OBJ element's corner as OBJ writes it -- "v", "v/vt", "v//vn" or "v/vt/vn" -- or empty
// when it is none of them ("11/", "1/2/", "/3"). The indices themselves are checked apart.
std::string obj_corner_form(const std::string& corner) {
  std::vector<std::string> parts(1);
  for (const char c : corner) {
    if (c == '/') {
      parts.emplace_back();
    } else {
      parts.back() += c;
    }
  }
  if (parts[0].empty() || parts.size() > 3) return {};
  if (parts.size() == 1) return "v";
  if (parts.size() == 2) return parts[1].empty() ? "" : "v/vt";
  if (parts[2].empty()) return {};
  return parts[1].empty() ? "v//vn" : "v/vt/vn";
}

}  // namespace

Status check_obj_structure(const std::string& text, const std::string& path) {
  if (auto bad = control_character_error(text, path, "OBJ")) return *bad;
  const auto fail = [&](int number, const std::string& what) {
    return Error{"mesh file " + path + " is not a readable mesh (OBJ, line " +
                 std::to_string(number) + ": " + what + ")"};
  };
  // Counts first (an index may name an element defined later in the file), and the vertex
  // data's numbers: assimp leaked the mesh of a vertex whose number ran into another byte
  // (fuzz/crashes/mesh/obj_vertex_number_runs_into_a_byte.obj).
  std::size_t counts[3] = {0, 0, 0};  // v, vt, vn
  {
    std::istringstream lines(text);
    std::string line;
    int number = 0;
    while (std::getline(lines, line)) {
      ++number;
      std::istringstream words(line);
      std::string first;
      words >> first;
      // As assimp dispatches: on the word's first letters, not the whole word ("vtx" is a
      // texture coordinate to it).
      const int kind = first.empty() || first[0] != 'v' ? -1
                       : first.size() == 1              ? 0
                       : first[1] == 't'                ? 1
                       : first[1] == 'n'                ? 2
                                                        : -1;
      if (kind < 0) continue;
      ++counts[kind];
      std::size_t values = 0;
      for (std::string word; words >> word && word[0] != '#'; ++values) {  // # a comment
        if (!is_decimal_number(word)) {
          return fail(number, "'" + first + "' takes numbers, not '" + word + "'");
        }
        // assimp counts a statement's numbers by their first character, a digit or a sign:
        // it read "v -0.01 .0 0.05" as two numbers, the vertices after it one short, and
        // leaked the mesh of a face naming the last
        // (fuzz/crashes/mesh/obj_number_begins_with_its_point.obj).
        if (word[0] == '.') {
          return fail(number, "'" + word + "' begins with its decimal point (write 0" + word +
                                  ", as assimp counts numbers by a digit or sign)");
        }
      }
      // v x y z [w | r g b], vt u [v [w]], vn x y z
      const bool fits = kind == 0   ? values == 3 || values == 4 || values == 6
                        : kind == 1 ? values >= 1 && values <= 3
                                    : values == 3;
      if (!fits) return fail(number, "'" + first + "' with " + std::to_string(values) + " numbers");
    }
  }
  std::istringstream lines(text);
  std::string line;
  int number = 0;
  while (std::getline(lines, line)) {
    ++number;
    std::istringstream words(line);
    std::string first;
    words >> first;
    // assimp's path filter steps over a "://" and past the name's end when it ends with one:
    // "mtllib fpy)file://" crashed it (fuzz/crashes/mesh/obj_mtllib_ends_with_a_url_scheme.obj).
    // A material library is a file beside the mesh, never a URL.
    if (first == "mtllib" && line.find("://") != std::string::npos) {
      return fail(number, "'mtllib' names a URL; a material library is a file beside the mesh");
    }
    // An element, to assimp, is any statement whose word begins with f, l or p: it read
    // "limitf 21//21 23//23 24//24" as a line and leaked the mesh
    // (fuzz/crashes/mesh/obj_statement_read_by_its_first_letter.obj).
    if (first.empty() || (first[0] != 'f' && first[0] != 'l' && first[0] != 'p')) continue;
    first = first.substr(0, 1);
    std::string corner, first_form;
    int corners = 0;
    while (words >> corner) {
      ++corners;
      std::size_t part = 0, begin = 0;
      while (part < 3) {
        const std::size_t end = std::min(corner.find('/', begin), corner.size());
        const std::string index = corner.substr(begin, end - begin);
        if (!index.empty()) {
          char* stop = nullptr;
          const long long i = std::strtoll(index.c_str(), &stop, 10);
          const std::size_t magnitude =
              static_cast<std::size_t>(i < 0 ? -(i + 1) + 1 : i);  // |i| without overflow
          if (*stop != '\0' || i == 0 || magnitude > counts[part]) {
            static const char* const kNames[] = {"vertex", "texture coordinate", "normal"};
            return fail(number, "'" + corner + "' names no " + kNames[part] + " of the file (" +
                                    std::to_string(counts[part]) + " defined)");
          }
        } else if (part == 0) {
          return fail(number, "'" + corner + "' has no vertex index");
        }
        if (end == corner.size()) break;
        begin = end + 1;
        ++part;
      }
      if (part >= 3) return fail(number, "'" + corner + "' has more than three indices");
      // Its form: v, v/vt, v//vn or v/vt/vn (no empty index but v//vn's), the same for every
      // corner of the element. assimp leaked the mesh of a face that mixed 'v//vn' with '11/'
      // and 'v' (fuzz/crashes/mesh/obj_face_mixes_its_corners_forms.obj).
      const std::string form = obj_corner_form(corner);
      if (form.empty()) return fail(number, "'" + corner + "' is not v, v/vt, v//vn or v/vt/vn");
      if (corners == 1) {
        first_form = form;
      } else if (form != first_form) {
        return fail(number, "'" + corner + "' is " + form + " where the first corner is " +
                                first_form + " (one form for every corner)");
      }
    }
    if (first == "f" && corners < 3) return fail(number, "a face needs three vertices");
    if (first == "l" && corners < 2) return fail(number, "a line needs two vertices");
  }
  return Status::Ok();
}

bool is_ascii_stl(const std::string& text) {
  std::size_t start = 0;
  while (start < text.size() && std::isspace(static_cast<unsigned char>(text[start]))) ++start;
  if (text.compare(start, 5, "solid") != 0) return false;
  // A binary STL may begin with "solid" too: assimp reads it as binary when its size is the
  // 84-byte header plus 50 bytes per facet it declares.
  if (text.size() >= 84) {
    std::uint32_t facets = 0;
    std::memcpy(&facets, text.data() + 80, sizeof facets);
    if (84 + 50 * static_cast<std::uint64_t>(facets) == text.size()) return false;
  }
  return true;
}

Status check_ascii_stl_structure(const std::string& text, const std::string& path) {
  if (auto bad = control_character_error(text, path, "ASCII STL")) return *bad;
  std::istringstream lines(text);
  std::string line;
  int number = 0;
  // The grammar as states: what the next line must start with.
  enum class Want { kSolid, kFacetOrEnd, kOuterLoop, kVertex, kEndLoop, kEndFacet, kAfterSolid };
  Want want = Want::kSolid;
  int vertices = 0;
  const auto fail = [&](const std::string& expected) {
    return Error{"mesh file " + path + " is not a readable mesh (ASCII STL, line " +
                 std::to_string(number) + ": expected " + expected + ")"};
  };
  // Decimal numbers only: assimp leaked the facets read on "vertex 0x01 0 0", which strtod
  // takes (fuzz/crashes/mesh/stl_hexadecimal_number.stl).
  const auto numbers = [](std::istringstream& words, int count) {
    for (int i = 0; i < count; ++i) {
      std::string word;
      if (!(words >> word) || !is_decimal_number(word)) return false;
    }
    return true;
  };
  while (std::getline(lines, line)) {
    ++number;
    std::istringstream words(line);
    std::string first;
    if (!(words >> first)) continue;  // blank line
    // assimp reads its three tokens -- facet, vertex, endsolid -- in lower case only: "vertEx"
    // leaked the facets read (fuzz/crashes/mesh/stl_vertex_not_in_lower_case.stl), as
    // "normAl" did. The words it skips over may be in any case: only those are folded.
    std::string lower = first;
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (lower != "facet" && lower != "vertex" && lower != "endsolid") first = lower;
    switch (want) {
      case Want::kSolid:
      case Want::kAfterSolid:
        if (first != "solid") return fail("'solid'");
        want = Want::kFacetOrEnd;
        break;
      case Want::kFacetOrEnd: {
        if (first == "endsolid") {
          want = Want::kAfterSolid;
          break;
        }
        // Lower case, as assimp reads it: "facet NORMAL" or "normAl" leaked the facets read
        // (fuzz/crashes/mesh/stl_normal_not_in_lower_case.stl).
        std::string normal;
        words >> normal;
        if (first != "facet" || normal != "normal" || !numbers(words, 3)) {
          return fail("'facet normal X Y Z' or 'endsolid'");
        }
        want = Want::kOuterLoop;
        break;
      }
      case Want::kOuterLoop: {
        std::string loop;
        words >> loop;
        for (char& c : loop) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        if (first != "outer" || loop != "loop") return fail("'outer loop'");
        want = Want::kVertex;
        vertices = 0;
        break;
      }
      case Want::kVertex:
        if (first != "vertex" || !numbers(words, 3)) return fail("'vertex X Y Z'");
        if (++vertices == 3) want = Want::kEndLoop;
        break;
      case Want::kEndLoop:
        if (first != "endloop") return fail("'endloop'");
        want = Want::kEndFacet;
        break;
      case Want::kEndFacet:
        if (first != "endfacet") return fail("'endfacet'");
        want = Want::kFacetOrEnd;
        break;
    }
  }
  if (want != Want::kAfterSolid) {
    ++number;
    return fail(want == Want::kSolid ? "'solid'" : "'endsolid' (the file ends inside a solid)");
  }
  return Status::Ok();
}

}  // namespace telear::geometry
