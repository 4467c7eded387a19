#pragma once
// Checks of an XML mesh file made before assimp reads it. Every XML format: elements nested deeper
// than kMaxNestingDepth (assimp's readers recurse once per level). COLLADA also: inputs on which assimp 5.2's COLLADA
// reader loops until memory runs out or reads outside its arrays, rejected with a message naming the line.
//
//  - Index lists: a primitive's <p> list is read as unsigned integers until the end of the text; a
//    character that is neither a digit nor whitespace is never consumed, and the reader appends
//    zeros until memory runs out (a 1 KB file with one stray byte took 12 GB and 40 s before
//    std::bad_alloc). <p>, <h> and <vcount> of <library_geometries> must hold digits and XML
//    whitespace only.
//  - Arrays and accessors: an accessor reads count elements of stride values from offset in its
//    source array, and assimp does not check that they lie inside it (a <float_array> without its
//    count attribute, or one shorter than its accessor, crashed it). Every <float_array>,
//    <int_array>, <bool_array>, <Name_array> and <IDREF_array> must have a count attribute, and
//    every <accessor> whose source is one of them must have offset + count * stride <= the array's
//    count.

#include <string>

namespace deepcheck::robots {

/// When `path` is an XML file (an XML format's extension, or '<' first), checks its nesting; when
/// it is a COLLADA file (extension .dae, or "<COLLADA" among its first bytes), applies the checks
/// above. Throws std::invalid_argument naming the file, the line and what is wrong. Other files
/// are left alone.
void checkXmlMeshFile(const std::string& path);

}  // namespace deepcheck::robots
