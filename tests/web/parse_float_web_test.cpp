// The web build's parseFloat (src/glint/core/parse_float_web.cpp: strtod and strtof behind
// std::from_chars' rules, for Emscripten's libc++ 13) compiled natively and checked against
// std::from_chars itself: the same values, ends and errors on numbers the scene, PLY and STL
// readers meet, and on what they must refuse.

#include <gtest/gtest.h>

#include <bit>
#include <charconv>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "glint/core/parse_float.h"

namespace glint {
namespace {

template <typename T>
void expectSameAsFromChars(const std::string& text) {
    const char* first = text.data();
    const char* last = first + text.size();
    T ours = T(-7), theirs = T(-7);
    auto a = parseFloat(first, last, ours);
    auto b = std::from_chars(first, last, theirs);
    EXPECT_EQ(a.ec, b.ec) << "'" << text << "'";
    EXPECT_EQ(a.ptr - first, b.ptr - first) << "'" << text << "'";
    if (b.ec == std::errc() && a.ec == std::errc()) {
        using Bits = std::conditional_t<sizeof(T) == 8, uint64_t, uint32_t>;
        if (theirs == theirs)  // NaN payloads aside
            EXPECT_EQ(std::bit_cast<Bits>(ours), std::bit_cast<Bits>(theirs)) << "'" << text << "'";
        else
            EXPECT_NE(ours, ours) << "'" << text << "'";
    }
}

template <typename T>
void expectAll(const std::vector<std::string>& texts) {
    for (const std::string& t : texts) expectSameAsFromChars<T>(t);
}

const std::vector<std::string> kCases = {"0",
                                         "-0",
                                         "1",
                                         "-1",
                                         "0.5",
                                         ".5",
                                         "5.",
                                         "1e3",
                                         "1E-3",
                                         "-2.5e+10",
                                         "3.14159265358979323846",
                                         "0.1",
                                         "0.30000000000000004",
                                         "1e308",
                                         "1e309",
                                         "-1e309",
                                         "1e-320",
                                         "1e-400",
                                         "1e38",
                                         "1e39",
                                         "3.4028235e38",
                                         "3.4028236e38",
                                         "1.17549435e-38",
                                         "1e-46",
                                         "inf",
                                         "-inf",
                                         "infinity",
                                         "INF",
                                         "nan",
                                         "-nan",
                                         "nan(123)",
                                         "",
                                         "-",
                                         "+1",
                                         " 1",
                                         "\t1",
                                         "e5",
                                         ".",
                                         "-.",
                                         "1e",
                                         "1e+",
                                         "0x1p3",
                                         "-0x10",
                                         "0x",
                                         "12abc",
                                         "1.5 2.5",
                                         "7,5",
                                         "1..2",
                                         "--1",
                                         "-+1",
                                         "1e5x",
                                         "123456789012345678901234567890",
                                         "0.000000000000000000000000000000000000000000001",
                                         "9007199254740993",
                                         "2.2250738585072011e-308"};

TEST(WebParseFloat, DoublesAsFromChars) { expectAll<double>(kCases); }

TEST(WebParseFloat, FloatsAsFromChars) { expectAll<float>(kCases); }

TEST(WebParseFloat, RandomNumbersAsFromChars) {
    std::mt19937_64 rng(167);
    std::vector<std::string> texts;
    for (int i = 0; i < 20000; ++i) {
        double v = std::bit_cast<double>(rng());
        if (!(v == v)) continue;
        char buf[64];
        auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 17 - i % 12);
        texts.emplace_back(buf, r.ptr);
    }
    expectAll<double>(texts);
    expectAll<float>(texts);
}

}  // namespace
}  // namespace glint
