#pragma once
// Mesh files checked before assimp reads them. assimp 5.2.5 (Debian 12's) crashes or leaks on
// some malformed files -- found by fuzz/mesh_fuzz.cpp: a COLLADA <triangles> with no <input>
// dereferences a null pointer, an ASCII STL cut inside a facet or an OBJ face naming a vertex
// the file lacks leaks the mesh -- so a hostile
// mesh named by a URDF could crash the program that loads it. The structure assimp's importers
// rely on is checked first, and a file that breaks it is refused with what is wrong.
//
// COLLADA:
//   - well-formed XML whose root element is <COLLADA>;
//   - every <input> has a semantic and a source "#id" naming an element of the file;
//   - every <vertices> has a POSITION input;
//   - every primitive of a <mesh> (<triangles>, <polylist>, <polygons>, <lines>, <linestrips>,
//     <tristrips>, <trifans>) has a VERTEX input and its index list (<p>; a <polylist> also
//     its <vcount>);
//   - every <accessor>, and every url or target "#id" of an instance, names an element.

#include <string>

#include "telear/core/result.hpp"

namespace telear::geometry {

// `text` is the file's content; `path` names it in the error.
Status check_collada_structure(const std::string& text, const std::string& path);

// ASCII STL (a file that starts with "solid" and is not a binary STL by its size): one or more
//   solid [name] { facet normal X Y Z  outer loop  vertex X Y Z (x3)  endloop  endfacet }
//   endsolid [name]
// numbers as numbers; a file cut short or with another word is refused
// with the line and what was expected.
Status check_ascii_stl_structure(const std::string& text, const std::string& path);

// Wavefront OBJ: every index of a face, line or point ('f', 'l', 'p'; v, v/vt, v//vn, v/vt/vn,
// negative ones counting back) names a vertex, texture coordinate or normal the file has, and
// is a number; a face has at least three vertices.
Status check_obj_structure(const std::string& text, const std::string& path);

// Whether assimp reads `text` (`size` bytes) as an ASCII STL: it starts with "solid" and its
// size is not that of the binary STL its header would describe.
bool is_ascii_stl(const std::string& text);

}  // namespace telear::geometry
