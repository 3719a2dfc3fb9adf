#include "lsdem/core/Sha256.h"

#include "lsdem/core/Error.h"

#include <openssl/evp.h>

#include <array>
#include <fstream>
#include <memory>

namespace lsdem {

namespace {

/// An OpenSSL SHA-256 digest in progress; any OpenSSL failure (out of memory, a provider
/// missing from a broken installation) becomes an Error naming @a source.
class Sha256Digest
{
public:
    explicit Sha256Digest(const std::string& source)
        : mContext(EVP_MD_CTX_new(), &EVP_MD_CTX_free), mSource(source)
    {
        if (!mContext || EVP_DigestInit_ex(mContext.get(), EVP_sha256(), nullptr) != 1)
            fail();
    }

    void update(const char* data, size_t size)
    {
        if (EVP_DigestUpdate(mContext.get(), data, size) != 1) fail();
    }

    /// Lower-case hex of the digest; call once.
    std::string hex()
    {
        std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
        unsigned int size = 0;
        if (EVP_DigestFinal_ex(mContext.get(), digest.data(), &size) != 1) fail();
        static const char* kHexDigits = "0123456789abcdef";
        std::string out;
        for (unsigned int i = 0; i < size; ++i) {
            out.push_back(kHexDigits[digest[i] >> 4]);
            out.push_back(kHexDigits[digest[i] & 0xf]);
        }
        return out;
    }

private:
    [[noreturn]] void fail() const
    {
        throw Error(mSource, "OpenSSL could not compute a SHA-256 digest",
                    "check the OpenSSL installation (libssl3)");
    }

    std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> mContext;
    std::string mSource;
};

} // namespace

std::string sha256Hex(const std::string& bytes)
{
    Sha256Digest digest("SHA-256 of a string");
    digest.update(bytes.data(), bytes.size());
    return digest.hex();
}

std::string sha256OfFile(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path, "cannot read the file to hash it");
    // In chunks: a scanned grain can be hundreds of megabytes.
    Sha256Digest digest(path);
    std::array<char, 1 << 16> chunk;
    while (in) {
        in.read(chunk.data(), std::streamsize(chunk.size()));
        digest.update(chunk.data(), size_t(in.gcount()));
    }
    if (in.bad()) throw Error(path, "reading the file failed while hashing it");
    return digest.hex();
}

} // namespace lsdem
