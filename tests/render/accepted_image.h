#pragma once
// The check every golden test of Glint's own features makes: the render against the image Glint
// made when the feature was accepted (regenerated only deliberately). Renders are
// deterministic; a few pixels one level off are tolerated for floating-point differences on
// another CPU, and at most 1% of pixels off by one level.

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "glint/io/image/image_io.h"
#include "glint/io/image/image_diff.h"

namespace glint::test {

inline void expectAcceptedImage(const Image8& ours, const std::string& referencePath,
                                const std::string& label) {
    Image8 reference = readImage8(referencePath, 3);
    ASSERT_EQ(ours.width, reference.width);
    ASSERT_EQ(ours.height, reference.height);
    long long hot1 = countHotPixels(ours, reference, 1);
    long long hot0 = countHotPixels(ours, reference, 0);
    std::printf("%s: pixels differing by more than 0 / 1 levels: %lld / %lld\n", label.c_str(),
                hot0, hot1);
    EXPECT_LE(hot1, 5) << "the image changed";
    EXPECT_LE(hot0, static_cast<long long>(ours.width) * ours.height / 100);
}

}  // namespace glint::test
