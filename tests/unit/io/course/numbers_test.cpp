#include "glint/io/course/numbers.h"

#include <gtest/gtest.h>

#include <bit>
#include <charconv>
#include <cstring>
#include <string>

#include "glint/math/rng.h"

namespace glint {
namespace {

/// What std::from_chars makes of the whole string (with one leading '+' allowed), if anything.
bool reference(const std::string& s, double& out) {
    const char* b = s.data();
    const char* e = b + s.size();
    if (b != e && *b == '+' && e - b > 1 && b[1] != '-' && b[1] != '+') ++b;
    auto [p, ec] = std::from_chars(b, e, out);
    return ec == std::errc() && p == e;
}

void expectSameAsFromChars(const std::string& s) {
    double fast = 0, ref = 0;
    bool took = parseDecimalFast(s.data(), s.data() + s.size(), fast);
    bool valid = reference(s, ref);
    if (took) {
        ASSERT_TRUE(valid) << "fast path accepted '" << s << "'";
        EXPECT_EQ(std::bit_cast<uint64_t>(fast), std::bit_cast<uint64_t>(ref)) << "'" << s << "'";
    }
}

TEST(Numbers, FastDecimalsEqualFromCharsBitForBit) {
    for (const char* s : {"0", "-0", "+0", "0.0", "-0.", ".5", "-.5", "+1", "5.", "1.6831",
                          "-3.0673", "0.000001234", "123456789012345", "1e5", "2E-4",
                          "1.5e+10", "9007199254740991", "0.1", "0.2", "0.3", "1e22", "1e-22",
                          "3.14159265358979", "1.7976931348623157e308"})
        expectSameAsFromChars(s);
    // Many random decimals of the kinds scene files hold.
    Rng rng(42);
    char buf[64];
    for (int i = 0; i < 200000; ++i) {
        double v = (static_cast<double>(rng.next()) - 2147483648.0) / (1u << (rng.next() % 31));
        int precision = static_cast<int>(rng.next() % 12);
        std::snprintf(buf, sizeof buf, i % 3 ? "%.*f" : "%.*e", precision, v);
        expectSameAsFromChars(buf);
    }
}

TEST(Numbers, FastDecimalsDeclineWhatTheyCannotReadExactly) {
    double v;
    for (const char* s : {"", ".", "-", "+", "e5", "1e", "1.5.3", "12abc", "+-1", "--1", "inf",
                          "nan", "1234567890123456789", "1e23", "1e-23", "0x10"}) {
        EXPECT_FALSE(parseDecimalFast(s, s + std::strlen(s), v)) << "'" << s << "'";
    }
}

TEST(Numbers, FastUnsignedIntegers) {
    long long v = -1;
    EXPECT_TRUE(parseUnsignedFast("640", "640" + 3, v));
    EXPECT_EQ(v, 640);
    EXPECT_TRUE(parseUnsignedFast("+12", "+12" + 3, v));
    EXPECT_EQ(v, 12);
    for (const char* s : {"", "+", "-1", "1.0", "12a", "1234567890123456789"})
        EXPECT_FALSE(parseUnsignedFast(s, s + std::strlen(s), v)) << "'" << s << "'";
}

}  // namespace
}  // namespace glint
