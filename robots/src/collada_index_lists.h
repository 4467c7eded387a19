#pragma once
// A check of COLLADA index lists made before assimp reads the file.
//
// assimp 5.2's COLLADA reader parses a primitive's <p> list by reading unsigned integers until the
// end of the text; a character that is neither a digit nor whitespace is never consumed, so the
// reader appends zeros until memory runs out (a 1 KB file with one stray byte in <p> took 12 GB
// and 40 s before std::bad_alloc). This check rejects such a file first, naming the line.

#include <string>

namespace deepcheck::robots {

/// When `path` is a COLLADA file (extension .dae, or "<COLLADA" among its first bytes), checks
/// that the <p>, <h> and <vcount> lists of <library_geometries> hold only digits and XML
/// whitespace. Throws std::invalid_argument naming the file, the line, the list and the offending
/// character otherwise. Other files are left alone.
void checkColladaIndexLists(const std::string& path);

}  // namespace deepcheck::robots
