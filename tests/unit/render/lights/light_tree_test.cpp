// The light tree (render/lights/light_tree.h): every light that can reach a point has a probability
// there, and they sum to at most one (a node whose bounds can reach the point may hold only
// lights that cannot: the draws that end there choose none, as pbrt-v4's do, which loses no
// light); sample() returns the probability pmf() gives (what multiple importance sampling
// relies on), its choices follow those probabilities, lights that cannot reach a point are
// never chosen, and near or bright lights are preferred.

#include "glint/render/lights/light_tree.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "glint/math/rng.h"

namespace glint {
namespace {

Vec3 randomIn(Rng& rng, double lo, double hi) {
    return Vec3(lo + (hi - lo) * rng.uniform(), lo + (hi - lo) * rng.uniform(),
                lo + (hi - lo) * rng.uniform());
}

Vec3 randomDirection(Rng& rng) {
    for (;;) {
        const Vec3 v = randomIn(rng, -1, 1);
        const double len = length(v);
        if (len > 0.1 && len <= 1) return v / len;
    }
}

/// Points, one-sided and two-sided triangles' bounds and spheres' bounds, of random power.
std::vector<LightBounds> mixedLights(int n, uint64_t seed) {
    Rng rng(seed);
    std::vector<LightBounds> lights;
    for (int i = 0; i < n; ++i) {
        const Vec3 c = randomIn(rng, -5, 5);
        const double phi = 0.1 + 10 * rng.uniform();
        switch (i % 4) {
            case 0:
                lights.push_back(LightBounds::point(c, phi));
                break;
            case 1:
            case 2: {
                const Vec3 a = c + randomIn(rng, -0.3, 0.3), b = c + randomIn(rng, -0.3, 0.3);
                const Vec3 facing = normalize(cross(a - c, b - c));
                lights.push_back(LightBounds::surface(min(c, min(a, b)), max(c, max(a, b)), phi,
                                                      facing, i % 4 == 2));
                break;
            }
            default:
                lights.push_back(
                    LightBounds::surface(c - Vec3(0.2), c + Vec3(0.2), phi, Vec3(0), false));
        }
    }
    return lights;
}

TEST(LightTree, EveryLightThatReachesAPointHasAProbabilityAndSampleReturnsIt) {
    // 17,000: a tree large enough to be built by median splits above small nodes.
    for (int n : {1, 2, 3, 17, 200, 17000}) {
        const std::vector<LightBounds> lights = mixedLights(n, 10 + n);
        const LightTree tree(lights);
        Rng rng(7);
        double mean = 0;
        const int trials = n > 1000 ? 5 : 50;
        for (int trial = 0; trial < trials; ++trial) {
            const Vec3 p = randomIn(rng, -7, 7);
            const Vec3 normal = trial % 3 == 0 ? Vec3(0) : randomDirection(rng);
            double total = 0;
            for (uint32_t k = 0; k < lights.size(); ++k) {
                const double q = tree.pmf(p, normal, k);
                total += q;
                if (lights[k].importance(p, normal) > 0) {
                    EXPECT_GT(q, 0) << n << " lights: light " << k << " reaches p but has none";
                }
            }
            EXPECT_LE(total, 1 + 1e-9) << n << " lights, trial " << trial;
            mean += total / trials;
            for (int draw = 0; draw < 20; ++draw) {
                const std::optional<LightTree::Choice> c = tree.sample(p, normal, rng.uniform());
                if (!c) continue;
                EXPECT_NEAR(c->probability, tree.pmf(p, normal, c->light), 1e-12 * c->probability);
                EXPECT_GT(c->probability, 0);
            }
        }
        // 1% of the draws is lost here with 17 and with 200 lights.
        EXPECT_GT(mean, 0.95) << n << " lights: the draws that choose none are few";
    }
}

TEST(LightTree, ChoicesFollowTheProbabilities) {
    const std::vector<LightBounds> lights = mixedLights(24, 3);
    const LightTree tree(lights);
    const Vec3 p(0.5, 1, -0.5), normal = normalize(Vec3(0.2, 1, 0.1));
    Rng rng(11);
    std::vector<int> counts(lights.size(), 0);
    int none = 0;
    const int trials = 200000;
    for (int i = 0; i < trials; ++i) {
        const std::optional<LightTree::Choice> c = tree.sample(p, normal, rng.uniform());
        if (c)
            counts[c->light]++;
        else
            ++none;
    }
    // Chi-square against the probabilities, the draws that chose none a cell of their own
    // (df at most 24): 99.9% of such draws stay below 51.2.
    double chi2 = 0, chosen = 0;
    for (uint32_t k = 0; k < lights.size(); ++k) chosen += tree.pmf(p, normal, k);
    int cells = 0;
    if (chosen < 1 - 1e-9) {
        const double expected = trials * (1 - chosen);
        chi2 += (none - expected) * (none - expected) / expected;
        ++cells;
    } else {
        EXPECT_EQ(none, 0);
    }
    for (uint32_t k = 0; k < lights.size(); ++k) {
        const double expected = trials * tree.pmf(p, normal, k);
        if (expected == 0) {
            EXPECT_EQ(counts[k], 0) << "light " << k << " has no probability but was chosen";
            continue;
        }
        chi2 += (counts[k] - expected) * (counts[k] - expected) / expected;
        ++cells;
    }
    EXPECT_GT(cells, 10);
    EXPECT_LT(chi2, 51.2);
}

TEST(LightTree, LightsThatCannotReachAPointAreNeverChosen) {
    // Two one-sided panels facing up at y = 1, one two-sided: below them only the two-sided
    // one can light a point; above, all three.
    const Vec3 up(0, 1, 0);
    std::vector<LightBounds> lights = {
        LightBounds::surface({-1, 1, -1}, {0, 1, 0}, 1, up, false),
        LightBounds::surface({0, 1, 0}, {1, 1, 1}, 1, up, false),
        LightBounds::surface({2, 1, 2}, {3, 1, 3}, 1, up, true),
    };
    const LightTree tree(lights);
    const Vec3 below(0.5, -2, 0.5), above(0.5, 3, 0.5);
    EXPECT_EQ(tree.pmf(below, Vec3(0), 0), 0);
    EXPECT_EQ(tree.pmf(below, Vec3(0), 1), 0);
    EXPECT_DOUBLE_EQ(tree.pmf(below, Vec3(0), 2), 1);
    for (uint32_t k = 0; k < 3; ++k) EXPECT_GT(tree.pmf(above, Vec3(0), k), 0);
}

TEST(LightTree, NearAndBrightLightsArePreferred) {
    // 64 equal lamps on a grid; a point just above one of them chooses it most often.
    std::vector<LightBounds> lights;
    for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j) {
            const Vec3 c(i * 2.0, 3, j * 2.0);
            lights.push_back(LightBounds::surface(c - Vec3(0.2, 0, 0.2), c + Vec3(0.2, 0, 0.2), 1,
                                                  Vec3(0, -1, 0), false));
        }
    const LightTree tree(lights);
    const Vec3 p(6, 2.5, 8);  // below lamp (3, 4)
    const uint32_t nearest = 3 * 8 + 4;
    double most = 0;
    uint32_t best = 0;
    for (uint32_t k = 0; k < lights.size(); ++k)
        if (tree.pmf(p, Vec3(0, 1, 0), k) > most) {
            most = tree.pmf(p, Vec3(0, 1, 0), k);
            best = k;
        }
    EXPECT_EQ(best, nearest);
    EXPECT_GT(most, 0.25);  // against 1/64 by power alone
    // Ten times the power raises a far lamp's share.
    lights[0].phi = 10;
    const LightTree brighter(lights);
    EXPECT_GT(brighter.pmf(p, Vec3(0, 1, 0), 0), tree.pmf(p, Vec3(0, 1, 0), 0));
}

TEST(LightTree, ManyLightsInALineKeepPathsWithinTheirBits) {
    // Equal points along a line, 20,000 of them: the tree must not run deeper than a light's
    // 64-bit path (it halves by count below a depth of 30).
    std::vector<LightBounds> lights;
    for (int i = 0; i < 20000; ++i) lights.push_back(LightBounds::point({i * 0.01, 0, 0}, 1));
    const LightTree tree(lights);
    double total = 0;
    for (uint32_t k = 0; k < lights.size(); ++k) total += tree.pmf({50, 1, 0}, Vec3(0), k);
    EXPECT_NEAR(total, 1, 1e-9);
}

}  // namespace
}  // namespace glint
