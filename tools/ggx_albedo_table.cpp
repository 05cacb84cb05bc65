// glint_ggx_albedo_table [OUTPUT]: computes the table of GGX directional albedos E(mu, alpha)
// of src/glint/render/bsdfs/ggx_albedo.h (its layout is there) and writes it as C++ to OUTPUT
// (standard output without one):
//
//   build/tools/glint_ggx_albedo_table src/glint/render/bsdfs/tables/ggx_albedo_table.cpp
//
// Run it when optics.h's GGX lobe or the table's layout changes; the unit tests recompute
// entries independently and fail when the committed table no longer matches. It takes a few
// minutes on two cores.
//
// How. E(mu, alpha) is the mean sample weight of the lobe with F = 1 sampled through visible
// normals: G1(wi) for wi the mirror of wo about the visible normal, 0 below the surface. The
// visible normals are Ggx::visibleNormal() of uniform points of the unit disk, so
//     E = (1 / pi) integral over the disk of G1(wi(p)) dp
//       = (1 / pi) integral_0^pi dphi integral_0^1 dt G1(wi(sqrt(t) sin phi, sqrt(t) cos phi)),
// using the mirror symmetry p1 -> -p1 (half the disk) and t = r^2 (dp = dt dphi / 2). Both
// integrals are adaptive Simpson quadratures to an absolute tolerance of 1e-8; the inner one is
// cut into panels crowding towards the rim t = 1, where for small alpha the few steep normals
// that send wi below the horizon all lie. Then:
//  - the values are rounded to float, as stored;
//  - each row's average 2 integral E mu dmu is computed of the row as interpolated (the lookup's
//    own rowValue() on the rounded values), by 16-point Gauss-Legendre rules per column cell in
//    the columns' measure w, where the interpolant is smooth: it is exact to rounding;
//  - the table's error is measured against the quadrature at the centre of every cell and the
//    midpoints of its edges (where bilinear interpolation errs most), and written with the table.

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <string>
#include <thread>
#include <vector>

#include "glint/math/quadrature.h"
#include "glint/render/bsdfs/ggx_albedo.h"
#include "glint/render/bsdfs/optics.h"

namespace {

using namespace glint;
using namespace glint::ggx_albedo_table;

constexpr double kPi = std::numbers::pi;
constexpr double kTolerance = 1e-8;

/// The integral of f over [a, b] to about `tolerance`, the interval first cut into `pieces`:
/// adaptive Simpson, each piece halved up to 40 times (deep: the table wants 1e-8).
template <typename F>
double integrate(const F& f, double a, double b, double tolerance, int pieces) {
    return integrateAdaptive(f, a, b, tolerance, pieces, 40);
}

/// E(mu, alpha) by quadrature over the disk of visible normals (see the top of the file).
double albedoByQuadrature(double mu, double alpha) {
    if (alpha == 0) return 1;
    Ggx ggx{alpha};
    Vec3 wo(std::sqrt(std::max(0.0, 1 - mu * mu)), 0, mu);
    auto overT = [&](double phi) {
        double sinPhi = std::sin(phi), cosPhi = std::cos(phi);
        auto weight = [&](double t) {
            double r = std::sqrt(t);
            Vec3 h = ggx.visibleNormal(wo, r * sinPhi, r * cosPhi);
            return ggx.g1(h * (2 * dot(wo, h)) - wo);
        };
        double sum = 0, a = 0;
        for (double b : {0.9, 0.99, 0.999, 1 - 1e-4, 1 - 1e-5, 1 - 1e-6, 1.0}) {
            sum += integrate(weight, a, b, kTolerance, 4);
            a = b;
        }
        return sum;
    };
    return integrate(overT, 0, kPi, kTolerance * kPi, 8) / kPi;
}

/// Runs job(k) for k in [0, n) on all cores.
void parallelFor(int n, const std::function<void(int)>& job) {
    std::atomic<int> next{0};
    std::vector<std::thread> threads;
    unsigned count = std::max(1u, std::thread::hardware_concurrency());
    for (unsigned t = 0; t < count; ++t)
        threads.emplace_back([&] {
            for (int k = next++; k < n; k = next++) job(k);
        });
    for (std::thread& t : threads) t.join();
}

using Table = std::array<std::array<float, kColumns>, kRows>;

/// E as the lookup (GgxAlbedo) interpolates it from `table`.
double interpolated(const Table& table, double mu, double alpha) {
    double r = rowOf(alpha);
    int row = std::clamp(static_cast<int>(r), 0, kRows - 2);
    double w = std::clamp(r - row, 0.0, 1.0);
    double m = measureOf(mu);
    return (1 - w) * rowValue(table[row].data(), rowAlpha(row), m) +
           w * rowValue(table[row + 1].data(), rowAlpha(row + 1), m);
}

/// 2 integral_0^1 E(mu) mu dmu of row `r` as interpolated, by Gauss-Legendre rules per column
/// cell in the columns' measure w (mu = w (2 - w), dmu = 2 (1 - w) dw), where the interpolant is
/// smooth.
double rowAverage(const Table& table, int r) {
    double alpha = rowAlpha(r);
    if (alpha == 0) return table[r][0];
    // 16-point Gauss-Legendre nodes on [-1, 1] (Newton's method on the Legendre polynomial).
    constexpr int kNodes = 16;
    std::array<double, kNodes> x{}, w{};
    for (int i = 0; i < kNodes; ++i) {
        double z = std::cos(kPi * (i + 0.75) / (kNodes + 0.5)), dp = 1;
        for (int iteration = 0; iteration < 100; ++iteration) {
            double p0 = 1, p1 = 0;
            for (int j = 1; j <= kNodes; ++j) {
                double p2 = p1;
                p1 = p0;
                p0 = ((2 * j - 1) * z * p1 - (j - 1) * p2) / j;
            }
            dp = kNodes * (z * p0 - p1) / (z * z - 1);
            double previous = z;
            z -= p0 / dp;
            if (std::abs(z - previous) < 1e-16) break;
        }
        x[i] = z;
        w[i] = 2 / ((1 - z * z) * dp * dp);
    }
    double sum = 0;
    for (int j = 0; j + 1 < kColumns; ++j) {
        double w0 = columnMeasure(j, alpha), w1 = columnMeasure(j + 1, alpha);
        double half = 0.5 * (w1 - w0), mid = 0.5 * (w0 + w1);
        for (int i = 0; i < kNodes; ++i) {
            double m = mid + half * x[i];
            sum += w[i] * half * rowValue(table[r].data(), alpha, m) * m * (2 - m) * 2 * (1 - m);
        }
    }
    return 2 * sum;
}

struct Check {
    double mu, alpha;
};

}  // namespace

int main(int argc, char** argv) {
    if (argc > 2) {
        std::fprintf(stderr, "usage: glint_ggx_albedo_table [OUTPUT]\n");
        return 2;
    }
    // The nodes: row 0 (alpha = 0) is 1; the others by quadrature.
    Table table{};
    table[0].fill(1);
    parallelFor((kRows - 1) * kColumns, [&](int k) {
        int r = 1 + k / kColumns, j = k % kColumns;
        double alpha = rowAlpha(r);
        double e = albedoByQuadrature(columnCosine(j, alpha), alpha);
        table[r][j] = static_cast<float>(std::min(e, 1.0));  // G1 <= 1: E <= 1 but for rounding
    });
    std::array<double, kRows> average{};
    for (int r = 0; r < kRows; ++r) average[r] = rowAverage(table, r);

    // The error: cell centres and edge midpoints, each row's columns in its own spacing.
    std::vector<Check> checks;
    for (int r = 0; r + 1 < kRows; ++r) {
        double alpha = rowAlpha(r + 1), mid = rowAlpha(r + 0.5);
        for (int j = 0; j < kColumns; ++j) {
            checks.push_back({columnCosine(j, mid), mid});  // between two rows
            if (j + 1 == kColumns) continue;
            checks.push_back({columnCosine(j + 0.5, alpha), alpha});  // between two columns
            checks.push_back({columnCosine(j + 0.5, mid), mid});      // the centre
        }
    }
    std::vector<double> errors(checks.size());
    parallelFor(static_cast<int>(checks.size()), [&](int k) {
        const Check& c = checks[k];
        errors[k] = interpolated(table, c.mu, c.alpha) - albedoByQuadrature(c.mu, c.alpha);
    });
    // The worst at alpha >= row 1's roughness, and below it.
    double alpha1 = rowAlpha(1);
    size_t worst = 0, worstBelow = 0;
    for (size_t k = 0; k < checks.size(); ++k) {
        size_t& w = checks[k].alpha >= alpha1 ? worst : worstBelow;
        if (w == 0 || std::abs(errors[k]) > std::abs(errors[w])) w = k;
    }
    // Bounds rounded up to two significant digits.
    auto bound = [](double e) {
        double scale = std::pow(10.0, std::floor(std::log10(std::abs(e))) - 1);
        return std::ceil(std::abs(e) / scale) * scale;
    };

    FILE* out = argc == 2 ? std::fopen(argv[1], "w") : stdout;
    if (!out) {
        std::fprintf(stderr, "glint_ggx_albedo_table: cannot write %s\n", argv[1]);
        return 1;
    }
    std::fprintf(
        out,
        "// Written by tools/ggx_albedo_table.cpp: do not edit. E(mu, alpha) of optics.h's "
        "GGX lobe\n// with F = 1, its rows' averages and the table's measured error; the "
        "layout is in\n// ggx_albedo.h.\n//\n");
    std::fprintf(
        out,
        "// Largest |E_table - E| at %zu points (every cell's centre and edge midpoints):\n"
        "//   alpha >= %.3g (row 1): %.2e, at alpha %.4f, mu %.4f;\n"
        "//   alpha <  %.3g: %.2e, at alpha %.6f, mu %.5f.\n\n",
        checks.size(), alpha1, std::abs(errors[worst]), checks[worst].alpha, checks[worst].mu,
        alpha1, std::abs(errors[worstBelow]), checks[worstBelow].alpha, checks[worstBelow].mu);
    std::fprintf(
        out, "#include \"glint/render/bsdfs/ggx_albedo.h\"\n\nnamespace glint::ggx_albedo_table {\n\n");
    std::fprintf(out, "const double kMaxError = %.2g;\n", bound(errors[worst]));
    std::fprintf(out, "const double kMaxErrorBelowRow1 = %.2g;\n\n", bound(errors[worstBelow]));
    std::fprintf(out, "// Six entries per line, as written.\n// clang-format off\n");
    std::fprintf(out, "const double kRowAlpha[kRows] = {\n");
    for (int r = 0; r < kRows; ++r) std::fprintf(out, "    %.17g,\n", rowAlpha(r));
    std::fprintf(out, "};\n\n");
    std::fprintf(out, "const double kAverage[kRows] = {\n");
    for (int r = 0; r < kRows; ++r) std::fprintf(out, "    %.17g,\n", average[r]);
    std::fprintf(out, "};\n\nconst float kAlbedo[kRows][kColumns] = {\n");
    for (int r = 0; r < kRows; ++r) {
        std::fprintf(out, "    // row %d: alpha %.6g\n    {", r, rowAlpha(r));
        for (int j = 0; j < kColumns; ++j) {
            std::string sep = j == 0 ? "" : (j % 6 == 0 ? ",\n     " : ", ");
            std::fprintf(out, "%s%#.9gf", sep.c_str(), table[r][j]);
        }
        std::fprintf(out, "},\n");
    }
    std::fprintf(out, "};\n// clang-format on\n\n}  // namespace glint::ggx_albedo_table\n");
    if (out != stdout && std::fclose(out) != 0) {
        std::fprintf(stderr, "glint_ggx_albedo_table: cannot write %s\n", argv[1]);
        return 1;
    }
    std::fprintf(stderr, "worst error %.3g (alpha >= %.3g), %.3g below\n", errors[worst], alpha1,
                 errors[worstBelow]);
    return 0;
}
