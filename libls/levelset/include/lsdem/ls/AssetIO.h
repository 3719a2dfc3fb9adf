/// @file AssetIO.h
/// @brief Read and write grain assets: one .vdb file holding the level set ("phi", a FloatGrid
///        of class level set, with the asset's metadata) and the surface nodes ("nodes", an
///        OpenVDB points grid with attributes). Any OpenVDB tool (vdb_print) can open it.
#pragma once

#include "lsdem/ls/GrainAsset.h"

#include <map>
#include <memory>
#include <mutex>
#include <string>

namespace lsdem {

/// Write @a asset to @a path atomically (temporary file in the same folder, then rename).
/// @throw Error if the folder is not writable, or if the asset's nodes have no normals (a
/// simulation's copy: save the asset it came from).
void saveAsset(const GrainAsset& asset, const std::string& path);

/// Whether loadAsset keeps the nodes' normals; a simulation skips them (SurfaceNodes::normals
/// says why). The file is checked the same either way.
enum class NodeNormals { Load, Skip };

/// Read an asset written by saveAsset.
/// @throw Error naming the file if it is missing, not a .vdb, corrupt, or not an lsdem asset.
std::shared_ptr<const GrainAsset> loadAsset(const std::string& path,
                                            NodeNormals normals = NodeNormals::Load);

/// Loads each asset file once and hands out shared, read-only copies: many grains, one asset.
/// The copies are whole (with normals). A load holds the library's lock while it runs its own
/// parallel loops: do not call get() from jobs that run in parallel.
class AssetLibrary
{
public:
    std::shared_ptr<const GrainAsset> get(const std::string& path);
    size_t size() const;

private:
    mutable std::mutex mMutex;
    std::map<std::string, std::shared_ptr<const GrainAsset>> mAssets;
};

} // namespace lsdem
