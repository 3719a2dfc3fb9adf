/// @file Sha256.h
/// @brief SHA-256 of a file's bytes (FIPS 180-4, computed by OpenSSL), for asset provenance;
///        matches `sha256sum`.
#pragma once

#include <string>

namespace lsdem {

/// Lower-case hex SHA-256 of @a bytes.
std::string sha256Hex(const std::string& bytes);

/// Lower-case hex SHA-256 of the file at @a path. @throw Error if it cannot be read.
std::string sha256OfFile(const std::string& path);

} // namespace lsdem
