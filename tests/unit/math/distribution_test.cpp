#include "glint/math/distribution.h"

#include <gtest/gtest.h>

#include "glint/math/rng.h"
#include "unit/statistics.h"

namespace glint {
namespace {

TEST(Distribution1D, DiscreteDrawsFollowTheWeights) {
    const std::vector<double> weights{1, 0, 3, 0.5, 0, 2.5};
    Distribution1D d(weights);
    EXPECT_DOUBLE_EQ(d.total(), 7);
    std::vector<double> observed(weights.size(), 0), expected;
    for (double w : weights) expected.push_back(w / 7 * 70000);
    Rng rng(7);
    for (int i = 0; i < 70000; ++i) {
        double p = 0, remapped = -1;
        size_t k = d.sampleDiscrete(rng.uniform(), &p, &remapped);
        ASSERT_GT(weights[k], 0) << "a cell of weight 0 was drawn";
        ASSERT_DOUBLE_EQ(p, weights[k] / 7);
        ASSERT_GE(remapped, 0);
        ASSERT_LT(remapped, 1);
        observed[k] += 1;
    }
    test::ChiSquareResult r = test::chiSquareTest(observed, expected);
    EXPECT_GT(r.pValue, 0.001) << "chi2 " << r.chi2;
}

TEST(Distribution1D, ContinuousDensityMatchesHistogram) {
    Distribution1D d({0.2, 1, 0, 4, 1.8});
    Rng rng(11);
    const int n = 50000, bins = 20;
    std::vector<double> observed(bins, 0), expected(bins, 0);
    for (int b = 0; b < bins; ++b) expected[b] = d.density((b + 0.5) / bins) / bins * n;
    for (int i = 0; i < n; ++i) {
        double pdf = 0;
        double x = d.sampleContinuous(rng.uniform(), &pdf);
        ASSERT_GE(x, 0);
        ASSERT_LT(x, 1);
        ASSERT_DOUBLE_EQ(pdf, d.density(x));
        observed[static_cast<int>(x * bins)] += 1;
    }
    EXPECT_EQ(observed[8] + observed[9] + observed[10] + observed[11], 0) << "zero cell sampled";
    test::ChiSquareResult r = test::chiSquareTest(observed, expected);
    EXPECT_GT(r.pValue, 0.001) << "chi2 " << r.chi2;
}

TEST(Distribution1D, AllZeroWeightsFallBackToUniform) {
    Distribution1D d({0, 0, 0, 0});
    EXPECT_DOUBLE_EQ(d.probability(2), 0.25);
    EXPECT_DOUBLE_EQ(d.density(0.9), 1);
    EXPECT_EQ(d.sampleDiscrete(0.6), 2u);
}

}  // namespace
}  // namespace glint
