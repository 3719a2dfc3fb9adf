/// @file AssetChecksum.h
/// @brief The SHA-256 seal of an asset file. OpenVDB trusts the sizes it reads from a file
///        (string lengths, compressed chunk sizes, node counts): a damaged .vdb can make it
///        allocate gigabytes or read out of bounds. So saveAsset stores the SHA-256 of the whole
///        file in the file-level metadata `lsdem_sha256`, and loadAsset checks it, with a parser
///        of its own that bounds every length by the file size, before OpenVDB sees the file.
///        Internal to lsdem_ls.
#pragma once

#include <string>

namespace lsdem {

/// The file-level metadata key holding the seal.
extern const char* const kAssetChecksumKey;

/// The level set grid's `lsdem_format`, naming a grain asset.
extern const char* const kAssetFormatName;

/// A placeholder of the seal's length, written by OpenVDB before sealAssetFile fills it in.
std::string unsealedAssetChecksum();

/// Compute the seal of the .vdb file @a tmpPath (written with the placeholder) and write it
/// into its place. @a path names the file in messages.
/// @throw Error if the file cannot be read or rewritten or has no placeholder.
void sealAssetFile(const std::string& tmpPath, const std::string& path);

/// Check the seal of the file at @a path: the header and the file-level metadata are parsed
/// with every length checked against the file size, then the SHA-256 of the bytes is compared,
/// then the grid descriptors and each grid's metadata and transform name are checked the same
/// way (a sealed file can be made by hand). The grids' trees are left to OpenVDB.
/// @throw Error naming the file if it is unreadable, malformed, unsealed or damaged.
void verifyAssetFile(const std::string& path);

/// Whether the file at @a path says it is an lsdem asset: its first bytes (the header and the
/// first grid's metadata) hold the seal's key or the asset format's name. Found by a plain
/// search, so a damaged header cannot pass an asset off as some other .vdb; such a file must
/// pass verifyAssetFile before OpenVDB reads it.
bool claimsToBeAsset(const std::string& path);

} // namespace lsdem
