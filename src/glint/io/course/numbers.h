#pragma once
/// Fast paths for reading the numbers scene files are made of. Each either gives exactly what
/// std::from_chars gives or declines, and the caller then asks std::from_chars.

#include <cstdint>

namespace glint {

/// The whole of [b, e) as a plain decimal: optional sign, digits with at most one '.', an
/// optional exponent. Succeeds only when the value is m * 10^k with an integer m < 2^53 and
/// |k| <= 22: both factors are then exact doubles and one correctly rounded multiplication or
/// division gives the correctly rounded result (Clinger's fast path, "How to read floating
/// point numbers accurately", PLDI 1990), the same double std::from_chars returns.
inline bool parseDecimalFast(const char* b, const char* e, double& out) {
    static constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                        1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                        1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
    bool negative = false;
    if (b != e && (*b == '-' || *b == '+')) negative = *b++ == '-';
    uint64_t m = 0;
    int digits = 0, fraction = 0;
    bool dot = false, sawDigit = false;
    for (; b != e; ++b) {
        char c = *b;
        if (c >= '0' && c <= '9') {
            sawDigit = true;
            if (m == 0 && c == '0') {
                if (dot) ++fraction;  // leading zeros after the point still scale
                continue;
            }
            if (++digits > 15) return false;  // keeps m below 10^15 < 2^53
            m = m * 10 + static_cast<uint64_t>(c - '0');
            if (dot) ++fraction;
        } else if (c == '.' && !dot) {
            dot = true;
        } else {
            break;
        }
    }
    if (!sawDigit) return false;  // "", ".", "-", "e5": not for the fast path
    int exponent = 0;
    if (b != e && (*b == 'e' || *b == 'E')) {
        ++b;
        bool expNegative = false;
        if (b != e && (*b == '-' || *b == '+')) expNegative = *b++ == '-';
        if (b == e) return false;
        for (; b != e && *b >= '0' && *b <= '9'; ++b) {
            exponent = exponent * 10 + (*b - '0');
            if (exponent > 1000) return false;
        }
        if (expNegative) exponent = -exponent;
    }
    if (b != e) return false;
    if (m == 0) {
        out = negative ? -0.0 : 0.0;
        return true;
    }
    int k = exponent - fraction;
    if (k < -22 || k > 22) return false;
    double v = static_cast<double>(m);
    v = k < 0 ? v / kPow10[-k] : v * kPow10[k];
    out = negative ? -v : v;
    return true;
}

/// The whole of [b, e) as digits with an optional '+', at most 18 of them.
inline bool parseUnsignedFast(const char* b, const char* e, long long& out) {
    if (b != e && *b == '+') ++b;
    if (b == e || e - b > 18) return false;
    long long v = 0;
    for (; b != e; ++b) {
        if (*b < '0' || *b > '9') return false;
        v = v * 10 + (*b - '0');
    }
    out = v;
    return true;
}

}  // namespace glint
