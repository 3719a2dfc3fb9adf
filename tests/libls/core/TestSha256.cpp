// SHA-256 against the FIPS 180-2 example vectors (appendix B) and a file hashed in chunks.
#include "lsdem/core/Sha256.h"

#include "lsdem/core/Error.h"
#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <fstream>

namespace {

const std::string kMillionA = "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0";

} // namespace

TEST(Sha256, MatchesPublishedVectors)
{
    EXPECT_EQ(lsdem::sha256Hex(""),
              "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
    // B.1: one block.
    EXPECT_EQ(lsdem::sha256Hex("abc"),
              "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    // B.2: 448 bits, so the padding spills into a second block.
    EXPECT_EQ(lsdem::sha256Hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
              "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
    // B.3: a million 'a'.
    EXPECT_EQ(lsdem::sha256Hex(std::string(1000000, 'a')), kMillionA);
}

// A million bytes span several read chunks; the file's digest must equal the string's.
TEST(Sha256, HashesAFileInChunks)
{
    lsdem::test::ScratchDir dir;
    const std::string path = dir.file("a.bin");
    std::ofstream(path, std::ios::binary) << std::string(1000000, 'a');
    EXPECT_EQ(lsdem::sha256OfFile(path), kMillionA);

    const std::string empty = dir.file("empty.bin");
    std::ofstream(empty, std::ios::binary).close();
    EXPECT_EQ(lsdem::sha256OfFile(empty), lsdem::sha256Hex(""));
}

TEST(Sha256, AMissingFileIsAnError)
{
    lsdem::test::ScratchDir dir;
    EXPECT_THROW(lsdem::sha256OfFile(dir.file("missing.stl")), lsdem::Error);
}
