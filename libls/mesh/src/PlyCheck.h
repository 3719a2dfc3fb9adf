// A PLY file checked before assimp reads it (private to lsdem_mesh). assimp 5.2 trusts a PLY
// header and body, and fuzzing found it never returning when end_header is missing, writing
// past its buffers when a keyword or a type is misspelt or a line is short, freeing memory
// twice for two elements of one name, and filling all memory on NULs in an ASCII body. So a
// file that starts like PLY (or is named .ply) is read here first: known keywords and types
// only, end_header within the first megabyte, and a body that holds the items the header
// announces. The check stays as long as Debian's assimp has these faults.
#pragma once

#include <string>

namespace lsdem {

/// @throw Error naming @a path (and the line, where it helps) if it is a damaged PLY file.
/// Files that are not PLY pass unread.
void checkPlyFile(const std::string& path);

} // namespace lsdem
