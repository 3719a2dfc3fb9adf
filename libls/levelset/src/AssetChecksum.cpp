#include "AssetChecksum.h"

#include "lsdem/core/Error.h"
#include "lsdem/core/Sha256.h"

#include <openvdb/points/StreamCompression.h>
#include <openvdb/version.h>

#include <cstdint>
#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <vector>

namespace lsdem {

const char* const kAssetChecksumKey = "lsdem_sha256";
const char* const kAssetFormatName = "lsdem-grain-asset";

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
    size_t offset() const { return mOffset; }
    void seek(size_t offset, const char* what)
    {
        if (offset > mBytes.size()) fail(std::string("the ") + what + " points past the end");
        mOffset = offset;
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
std::optional<size_t> findChecksum(ByteReader& in)
{
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

/// Bytes of the fixed-size metadata types OpenVDB registers: it reads exactly this many
/// whatever size the file states, so a different size would put its reading out of step.
size_t fixedMetadataSize(const std::string& type)
{
    static const std::map<std::string, size_t> sizes = {
        {"bool", 1},   {"int32", 4},  {"int64", 8},  {"float", 4},  {"double", 8},
        {"vec2i", 8},  {"vec2s", 8},  {"vec2d", 16}, {"vec3i", 12}, {"vec3s", 12},
        {"vec3d", 24}, {"vec4i", 16}, {"vec4s", 16}, {"vec4d", 32}, {"mat4s", 64},
        {"mat4d", 128}};
    const auto it = sizes.find(type);
    return it == sizes.end() ? 0 : it->second;
}

/// OpenVDB's per-grid index of leaf buffers (io/DelayedLoadMetadata.cc): a leaf count, then a
/// mask byte and a compressed size per leaf, each array raw or as a blosc frame. OpenVDB sizes
/// its arrays from the count and from the frame's own header before reading them, so both must
/// agree with the bytes there are. Read from @a start, @a size bytes.
void checkDelayedLoadMetadata(ByteReader& in, size_t start, std::uint32_t size)
{
    const size_t after = in.offset();
    in.seek(start, "leaf index");
    const size_t end = start + size;
    const auto count = in.read<std::uint32_t>("leaf index");
    const auto checkArray = [&](std::uint32_t bytes, size_t itemSize) {
        const size_t raw = size_t{count} * itemSize;
        const size_t stored = bytes > 0 ? size_t{bytes} : raw;
        if (stored > end - std::min(end, in.offset()))
            in.fail("a leaf index larger than its metadata");
        if (bytes > 0) {
            // A blosc frame: a 16-byte header whose second word is the uncompressed size,
            // which OpenVDB pads to at least BLOSC_PAD_BYTES.
            if (bytes < 16) in.fail("a leaf index frame shorter than its header");
            const size_t frame = in.skip(bytes, "leaf index");
            in.seek(frame + 4, "leaf index");
            const size_t unpacked = in.read<std::uint32_t>("leaf index");
            const size_t padded = std::max<size_t>(raw, openvdb::compression::BLOSC_PAD_BYTES);
            if (unpacked < raw || unpacked > padded)
                in.fail("a leaf index frame of the wrong size");
            in.seek(frame + bytes, "leaf index");
        } else {
            in.skip(raw, "leaf index");
        }
    };
    checkArray(in.read<std::uint32_t>("leaf index"), sizeof(std::int8_t));  // the masks
    const auto sizesBytes = in.read<std::uint32_t>("leaf index");
    if (sizesBytes != std::numeric_limits<std::uint32_t>::max())  // max: no sizes stored
        checkArray(sizesBytes, sizeof(std::int64_t));
    if (in.offset() > end) in.fail("a leaf index larger than its metadata");
    in.seek(after, "leaf index");
}

/// The grid descriptors and each grid's compression flags, metadata and transform name, read
/// the way OpenVDB reads them (io/Archive.cc, io/GridDescriptor.cc, MetaMap::readMeta), each
/// length bounded by the grid's own byte range. The trees that follow are not parsed here.
void checkGridHeaders(ByteReader& in)
{
    const auto count = in.read<std::int32_t>("grid count");
    if (count < 1 || count > 64) in.fail("a grid count of " + std::to_string(count));
    struct Range
    {
        std::int64_t grid, block, end;
    };
    std::vector<Range> ranges;
    for (std::int32_t i = 0; i < count; ++i) {
        in.string("grid descriptor");  // the grid's unique name
        in.string("grid descriptor");  // its type
        in.string("grid descriptor");  // the grid it instances, if any
        Range r{};
        r.grid = in.read<std::int64_t>("grid descriptor");
        r.block = in.read<std::int64_t>("grid descriptor");
        r.end = in.read<std::int64_t>("grid descriptor");
        if (!(static_cast<std::int64_t>(in.offset()) <= r.grid && r.grid <= r.block &&
              r.block <= r.end))
            in.fail("grid " + std::to_string(i) + " has its data out of order");
        in.seek(static_cast<size_t>(r.end), "grid descriptor");
        ranges.push_back(r);
    }
    for (const Range& r : ranges) {
        in.seek(static_cast<size_t>(r.grid), "grid");
        in.read<std::uint32_t>("grid compression flags");
        const auto entries = in.read<std::int32_t>("grid metadata");
        if (entries < 0) in.fail("a negative metadata count");
        for (std::int32_t e = 0; e < entries; ++e) {
            in.string("grid metadata");
            const std::string type = in.string("grid metadata");
            const auto size = in.read<std::uint32_t>("grid metadata");
            const size_t fixed = fixedMetadataSize(type);
            if (fixed != 0 && size != fixed)
                in.fail("grid metadata of type " + type + " stored in " +
                        std::to_string(size) + " bytes");
            const size_t start = in.skip(size, "grid metadata");
            if (type == "__delayedload" && size > 0) checkDelayedLoadMetadata(in, start, size);
        }
        in.string("grid transform");  // the map's type name; its numbers have fixed sizes
        if (in.offset() > static_cast<size_t>(r.block))
            in.fail("a grid's header runs into its tree");
    }
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
    ByteReader in(bytes, path);
    const std::optional<size_t> at = findChecksum(in);
    if (!at) throw Error(path, "cannot seal the asset: OpenVDB wrote no checksum placeholder");
    const std::string checksum = checksumOf(bytes, *at);
    std::fstream out(tmpPath, std::ios::binary | std::ios::in | std::ios::out);
    out.seekp(static_cast<std::streamoff>(*at));
    out.write(checksum.data(), static_cast<std::streamsize>(checksum.size()));
    out.close();
    if (!out) throw Error(path, "cannot write the asset's checksum (disk full?)");
}

bool claimsToBeAsset(const std::string& path)
{
    const size_t prefixBytes = 1 << 20;  // far beyond the header and the level set's metadata
    std::ifstream in(path, std::ios::binary);
    std::string prefix(prefixBytes, '\0');
    in.read(prefix.data(), static_cast<std::streamsize>(prefix.size()));
    prefix.resize(static_cast<size_t>(in.gcount()));
    return prefix.find(kAssetChecksumKey) != std::string::npos ||
           prefix.find(kAssetFormatName) != std::string::npos;
}

void verifyAssetFile(const std::string& path)
{
    std::string bytes = readWholeFile(path);
    ByteReader in(bytes, path);
    const std::optional<size_t> at = findChecksum(in);
    if (!at)
        throw Error(path, "the asset has no checksum (" + std::string(kAssetChecksumKey) +
                              "): it was baked by an older lsdem or written by another program",
                    "bake it again with lsdem-bake");
    const std::string stored = bytes.substr(*at, kChecksumLength);
    if (checksumOf(bytes, *at) != stored)
        throw Error(path, "the file is damaged: its SHA-256 differs from the one stored when it "
                          "was written (truncated, or changed since)",
                    "copy it again from where it came from, or bake it again with lsdem-bake");
    // A sealed file can still be made by hand: its headers are checked too. (The trees after
    // them are OpenVDB's to read; see docs/fuzzing.md.)
    checkGridHeaders(in);
}

} // namespace lsdem
