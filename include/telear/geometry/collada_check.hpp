#pragma once
// COLLADA files checked before assimp reads them. assimp 5.2.5 (Debian 12's) dereferences a
// null pointer on some malformed documents -- found by fuzz/mesh_fuzz.cpp: a <triangles> with
// no <input> -- so a hostile mesh named by a URDF could crash the program that loads it. The
// structure assimp's COLLADA importer relies on is checked first, and a file that breaks it is
// refused with what is missing:
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

}  // namespace telear::geometry
