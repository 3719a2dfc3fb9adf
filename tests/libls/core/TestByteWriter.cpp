// lsdem's binary writer and reader (lsdem/core/ByteWriter.h, ByteReader.h), which checkpoints,
// the ranks' grain exchange and study records share: every number comes back bit for bit,
// every string byte for byte, and bytes read with the wrong layout, cut short or damaged are
// refused (DamagedBytes) before anything is read out of bounds or allocated for them.
#include "lsdem/core/ByteReader.h"
#include "lsdem/core/ByteWriter.h"

#include <gtest/gtest.h>

#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

using namespace lsdem;

namespace {

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

} // namespace

TEST(ByteWriter, NumbersIntegersAndTextComeBackExactly)
{
    double nanWithPayload;
    const unsigned long long bits = 0x7ff8000000abcdefULL;
    std::memcpy(&nanWithPayload, &bits, sizeof bits);
    const std::vector<double> numbers = {0.0, -0.0, 1.0 / 3.0, std::numeric_limits<double>::denorm_min(),
                                         std::numeric_limits<double>::max(), -INFINITY, nanWithPayload,
                                         1e-300};
    const char raw[] = "a,b\n\"c\"\0δ";  // a NUL inside, UTF-8 after it
    const std::string text(raw, sizeof raw - 1);
    ByteWriter<> out;
    for (double v : numbers) out.number(v);
    out.integer(LLONG_MIN).integer(LLONG_MAX).integer(-1).text(text).text("").numbers(numbers).numbers({});

    ByteReader in(out.bytes());
    for (double v : numbers) EXPECT_TRUE(sameBits(in.number(), v)) << v;
    EXPECT_EQ(in.integer(), LLONG_MIN);
    EXPECT_EQ(in.integer(), LLONG_MAX);
    EXPECT_EQ(in.integer(), -1);
    EXPECT_EQ(in.text(), text);
    EXPECT_EQ(in.text(), "");
    const std::vector<double> back = in.numbers();
    ASSERT_EQ(back.size(), numbers.size());
    for (size_t i = 0; i < back.size(); ++i) EXPECT_TRUE(sameBits(back[i], numbers[i])) << i;
    EXPECT_TRUE(in.numbers().empty());
    EXPECT_TRUE(in.atEnd());
}

TEST(ByteWriter, AWrongLayoutIsRefused)
{
    ByteWriter<> out;
    out.number(1.5).text("abc");
    {
        ByteReader in(out.bytes());
        in.number();
        in.text();
        EXPECT_THROW(in.number(), DamagedBytes);  // past the end
    }
    {
        // Read as a list of numbers: a length of 3 items needs 24 bytes, there are 3.
        ByteReader in(out.bytes());
        in.number();
        EXPECT_THROW(in.numbers(), DamagedBytes);
    }
    {
        // A length that is not one (the bits of 1.5 read as an integer): refused, not allocated.
        ByteReader in(out.bytes());
        EXPECT_THROW(in.text(), DamagedBytes);
    }
}

TEST(ByteWriter, AppendsToABufferGivenOrItsOwn)
{
    std::vector<char> given = {'x'};
    ByteWriter w(given);
    w.value<int32_t>(7).raw("ab", 2);
    ASSERT_EQ(given.size(), 1u + 4u + 2u);  // appended after what was there
    EXPECT_EQ(given[0], 'x');
    ByteReader in(given.data() + 1, given.data() + given.size());
    EXPECT_EQ(in.value<int32_t>(), 7);
    EXPECT_TRUE(in.skipIfNext("ab", 2));
    EXPECT_TRUE(in.atEnd());

    // A writer with its own buffer keeps it when moved (the buffer moves with it).
    ByteWriter<> own;
    own.text("kept");
    ByteWriter<> moved(std::move(own));
    moved.integer(3);
    ByteReader back(moved.bytes());
    EXPECT_EQ(back.text(), "kept");
    EXPECT_EQ(back.integer(), 3);
    EXPECT_TRUE(back.atEnd());
}

TEST(ByteReader, SkipsOnlyWhatMatches)
{
    const std::string bytes = "MAGICrest";
    ByteReader in(bytes);
    EXPECT_FALSE(in.skipIfNext("MAGIX", 5));
    EXPECT_EQ(in.left(), bytes.size());  // nothing consumed
    EXPECT_FALSE(in.skipIfNext("MAGICrestmore", 13));  // longer than what is left
    EXPECT_TRUE(in.skipIfNext("MAGIC", 5));
    EXPECT_EQ(in.left(), 4u);
}

// Every prefix of a record, and the record with each byte's bits flipped in turn, is either read
// to the end or refused with DamagedBytes: never a read past the end, a crash or a huge list.
TEST(ByteReader, ACutOrDamagedRecordIsRefusedNeverOverread)
{
    ByteWriter<> out;
    out.text("grain").list(std::vector<double>{1.0, 2.0, 3.0}).list(std::vector<uint64_t>{9});
    const std::string whole = out.bytes();
    const auto readAll = [](const std::string& bytes) {
        ByteReader in(bytes);
        in.text();
        in.numbers();
        in.list<uint64_t>();
        return in.atEnd();
    };
    EXPECT_TRUE(readAll(whole));
    for (size_t n = 0; n < whole.size(); ++n)
        EXPECT_THROW(readAll(whole.substr(0, n)), DamagedBytes) << "cut at " << n;
    int refused = 0;
    for (size_t at = 0; at < whole.size(); ++at) {
        std::string damaged = whole;
        damaged[at] = static_cast<char>(~damaged[at]);
        try {
            readAll(damaged);
        } catch (const DamagedBytes&) {
            ++refused;
        }
    }
    // Flipping any byte of a count (5, 3, 1) makes it larger than what is left: the three
    // counts' 24 bytes are refused. A flipped character or number is still a valid record.
    EXPECT_EQ(refused, 24);
}
