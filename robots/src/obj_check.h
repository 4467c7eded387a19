#pragma once
// A check of a mesh file made before assimp reads it, for assimp 5.2's OBJ reader. The reader
// copies each line into a buffer the size of the file, ends it with '\n' but no NUL, and reads the
// indices of a face ('f'), line ('l') or point ('p') statement with atoi. When that line is all
// of the file (a file of one line), atoi is handed a string without a terminator. Such a file
// cannot be a mesh: an OBJ mesh needs its vertices and its faces on separate lines.

#include <string>

namespace deepcheck::robots {

/// Throws std::invalid_argument naming the file when it holds at most one line end ('\n', '\r',
/// '\f' or NUL) and its first character (after a leading line end and a UTF-8 byte order mark) starts a
/// face, line or point statement. Any extension: assimp also reads a file as OBJ by its content.
void checkObjMeshFile(const std::string& path);

}  // namespace deepcheck::robots
