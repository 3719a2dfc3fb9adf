#include "AssetChecksum.h"

#include "lsdem/ls/Error.h"
#include "lsdem/ls/Sha256.h"

#include <openvdb/version.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <optional>

namespace lsdem {

const char* const kAssetChecksumKey = "lsdem_sha256";

namespace {

const size_t kChecksumLength = 64;  // hex digits of a SHA-256
const char* const kRebake = "the file is damaged or not an lsdem asset; bake it again with "
                            "lsdem-bake";

/// Reads the fixed-size fields at the start of a .vdb held in memory; running past the end is
/// an Error, never an out-of-bounds read.
class ByteReader
{
public:
    ByteReader(const std::string& bytes, const std::string& path) : mBytes(bytes), mPath(path) {}

    template <typename T>
    T read(const char* what)
    {
        T value;
        std::memcpy(&value, take(sizeof(T), what), sizeof(T));
        return value;
    }
    /// OpenVDB's strings: a 32-bit length, then the characters.
    std::string string(const char* what)
    {
        const auto length = read<std::uint32_t>(what);
        return std::string(take(length, what), length);
    }
    /// Skip @a count bytes; returns the offset where they start.
    size_t skip(size_t count, const char* what)
    {
        const size_t start = mOffset;
        take(count, what);
        return start;
    }
    [[noreturn]] void fail(const std::string& problem) const
    {
        throw Error(mPath, "not a readable lsdem asset: " + problem, kRebake);
    }

private:
    const char* take(size_t count, const char* what)
    {
        if (count > mBytes.size() - mOffset)
            fail(std::string("the file ends inside the ") + what);
        const char* at = mBytes.data() + mOffset;
        mOffset += count;
        return at;
    }

    const std::string& mBytes;
    const std::string& mPath;
    size_t mOffset = 0;
};

std::string readWholeFile(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.good() && !in.eof())
        throw Error(path, "the file cannot be read", "check its permissions");
    return bytes;
}

/// The offset of the seal's hex digits in @a bytes, or nothing if the file has no seal. The
/// header layout is OpenVDB's (io/Archive.cc, file format 222 and later).
std::optional<size_t> findChecksum(const std::string& bytes, const std::string& path)
{
    ByteReader in(bytes, path);
    if (in.read<std::int64_t>("header") != openvdb::OPENVDB_MAGIC)
        in.fail("it does not start like an OpenVDB file");
    const auto version = in.read<std::uint32_t>("header");
    if (version < 222 || version > openvdb::OPENVDB_FILE_VERSION)
        in.fail("OpenVDB file format " + std::to_string(version) + ", where lsdem writes " +
                std::to_string(openvdb::OPENVDB_FILE_VERSION));
    in.skip(2 * sizeof(std::uint32_t), "header");  // the library version that wrote it
    if (in.read<char>("header") != 1) in.fail("its grids are not indexed");
    in.skip(36, "header");  // the file's UUID, as text

    const auto count = in.read<std::int32_t>("file metadata");
    if (count < 0) in.fail("a negative metadata count");
    std::optional<size_t> found;
    for (std::int32_t i = 0; i < count; ++i) {
        const std::string name = in.string("file metadata");
        const std::string type = in.string("file metadata");
        const auto size = in.read<std::uint32_t>("file metadata");
        const size_t at = in.skip(size, "file metadata");
        if (name == kAssetChecksumKey && type == "string" && size == kChecksumLength)
            found = at;
    }
    return found;
}

/// The seal of @a bytes: SHA-256 of the file with the seal's digits set to the placeholder
/// (done in place: assets can be large).
std::string checksumOf(std::string& bytes, size_t at)
{
    bytes.replace(at, kChecksumLength, unsealedAssetChecksum());
    return sha256Hex(bytes);
}

} // namespace

std::string unsealedAssetChecksum() { return std::string(kChecksumLength, '0'); }

void sealAssetFile(const std::string& tmpPath, const std::string& path)
{
    std::string bytes = readWholeFile(tmpPath);
    const std::optional<size_t> at = findChecksum(bytes, path);
    if (!at) throw Error(path, "cannot seal the asset: OpenVDB wrote no checksum placeholder");
    const std::string checksum = checksumOf(bytes, *at);
    std::fstream out(tmpPath, std::ios::binary | std::ios::in | std::ios::out);
    out.seekp(static_cast<std::streamoff>(*at));
    out.write(checksum.data(), static_cast<std::streamsize>(checksum.size()));
    out.close();
    if (!out) throw Error(path, "cannot write the asset's checksum (disk full?)");
}

void verifyAssetFile(const std::string& path)
{
    std::string bytes = readWholeFile(path);
    const std::optional<size_t> at = findChecksum(bytes, path);
    if (!at)
        throw Error(path, "the asset has no checksum (" + std::string(kAssetChecksumKey) +
                              "): it was baked by an older lsdem or written by another program",
                    "bake it again with lsdem-bake");
    const std::string stored = bytes.substr(*at, kChecksumLength);
    if (checksumOf(bytes, *at) != stored)
        throw Error(path, "the file is damaged: its SHA-256 differs from the one stored when it "
                          "was written (truncated, or changed since)",
                    "copy it again from where it came from, or bake it again with lsdem-bake");
}

} // namespace lsdem
