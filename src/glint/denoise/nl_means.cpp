#include "glint/denoise/nl_means.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace glint::denoise_detail {
namespace {

// The image is filtered in tiles of this size (fixed, so that the work never depends on the
// thread count; every pixel's sums are formed in the same order whatever the tiling). A tile and
// its window's neighbourhood stay in the second-level cache for all the window's offsets.
constexpr int kTileWidth = 64;
constexpr int kTileHeight = 32;

// The colour distance's denominator floor: with zero variance, any difference rejects.
constexpr float kVarianceFloor = 1e-10f;

struct Tile {
    int x0, x1, y0, y1;
};

// Scratch for one tile, reused across the offsets.
struct TileScratch {
    std::vector<float> distance;  // per-pixel colour distance, the tile grown by the patch
    std::vector<float> rowSum;    // its sums along rows over the patch
    std::vector<float> total;     // one row's total distances, then weights
    std::vector<float> acc[27];   // the sums of Sum below
};

// The sums per pixel: the weight, the weighted values, the squared weights times the values'
// variances, and for a first-order fit the weighted moments of the offset (x, y) over the
// window's radius and of the values times it.
enum Sum {
    kW,
    kV,  // 3 channels
    kVar = kV + 3,
    kX = kVar + 3,
    kY,
    kXX,
    kXY,
    kYY,
    kXV,  // 3 channels
    kYV = kXV + 3,
    // A first-order fit's sums over one row of offsets (dy fixed): weight, times x, times x^2,
    // times the values, times x and the values (addRowSums).
    kRowW = kYV + 3,
    kRowX,
    kRowXX,
    kRowV,  // 3 channels
    kRowXV = kRowV + 3,
    kSumCount = kRowXV + 3
};

// The row loops, each over n pixels, with every pointer restrict so that they vectorise.

// d = the colour distance of p and q summed over the channels.
void colourDistance(int n, float* __restrict d, const float* __restrict p0,
                    const float* __restrict p1, const float* __restrict p2,
                    const float* __restrict q0, const float* __restrict q1,
                    const float* __restrict q2, const float* __restrict vp0,
                    const float* __restrict vp1, const float* __restrict vp2,
                    const float* __restrict vq0, const float* __restrict vq1,
                    const float* __restrict vq2, float alpha, float k2) {
    auto term = [=](float a, float b, float va, float vb) {
        const float diff = a - b;
        return (diff * diff - alpha * (va + std::min(va, vb))) / (kVarianceFloor + k2 * (va + vb));
    };
    for (int x = 0; x < n; ++x)
        d[x] = term(p0[x], q0[x], vp0[x], vq0[x]) + term(p1[x], q1[x], vp1[x], vq1[x]) +
               term(p2[x], q2[x], vp2[x], vq2[x]);
}

// r[x] = the sum of d[x - f .. x + f].
template <int F>
void rowSums(int n, float* __restrict r, const float* __restrict d) {
    for (int x = 0; x < n; ++x) {
        float sum = d[x - F];
        for (int i = -F + 1; i <= F; ++i) sum += d[x + i];
        r[x] = sum;
    }
}

// out[x] = max(0, norm * the sum of rows[0 .. 2f][x]).
template <int F>
void columnSums(int n, float* __restrict out, const float* const* rows, float norm) {
    if constexpr (F == 0) {
        const float* __restrict r0 = rows[0];
        for (int x = 0; x < n; ++x) out[x] = std::max(r0[x] * norm, 0.0f);
    } else if constexpr (F == 1) {
        const float* __restrict r0 = rows[0];
        const float* __restrict r1 = rows[1];
        const float* __restrict r2 = rows[2];
        for (int x = 0; x < n; ++x) out[x] = std::max((r0[x] + r1[x] + r2[x]) * norm, 0.0f);
    } else {
        const float* __restrict r0 = rows[0];
        for (int x = 0; x < n; ++x) out[x] = r0[x];
        for (int j = 1; j <= 2 * F; ++j) {
            const float* __restrict rj = rows[j];
            for (int x = 0; x < n; ++x) out[x] += rj[x];
        }
        for (int x = 0; x < n; ++x) out[x] = std::max(out[x] * norm, 0.0f);
    }
}

void patchSums(int f, int n, float* __restrict r, const float* __restrict d) {
    switch (f) {
        case 0:
            return rowSums<0>(n, r, d);
        case 1:
            return rowSums<1>(n, r, d);
        case 2:
            return rowSums<2>(n, r, d);
        case 3:
            return rowSums<3>(n, r, d);
        default:
            return rowSums<3>(n, r, d);  // nlMeans clamps f to 3
    }
}

void patchColumns(int f, int n, float* __restrict out, const float* const* rows, float norm) {
    if (f == 0) return columnSums<0>(n, out, rows, norm);
    if (f == 1) return columnSums<1>(n, out, rows, norm);
    return columnSums<2>(n, out, rows, norm);  // any f > 1: the general loop
}

// d += weight * |p - q|^2 over three channels.
void addVectorDistance(int n, float* __restrict d, const float* __restrict p0,
                       const float* __restrict p1, const float* __restrict p2,
                       const float* __restrict q0, const float* __restrict q1,
                       const float* __restrict q2, float weight) {
    for (int x = 0; x < n; ++x) {
        const float e0 = p0[x] - q0[x], e1 = p1[x] - q1[x], e2 = p2[x] - q2[x];
        d[x] += weight * (e0 * e0 + e1 * e1 + e2 * e2);
    }
}

// d += weight * ((depth_q - the plane through p at q) / depth_p)^2.
void addDepthDistance(int n, float* __restrict d, const float* __restrict dp,
                      const float* __restrict dq, const float* __restrict gx,
                      const float* __restrict gy, float dx, float dy, float weight) {
    for (int x = 0; x < n; ++x) {
        const float e = dq[x] - dp[x] - gx[x] * dx - gy[x] * dy;
        d[x] += weight * e * e / (dp[x] * dp[x] + 1e-12f);
    }
}

// Turns the distances into weights and adds them and the weighted values up.
void accumulate(int n, float* __restrict d, float* __restrict w, float* __restrict a0,
                float* __restrict a1, float* __restrict a2, const float* __restrict v0,
                const float* __restrict v1, const float* __restrict v2) {
    for (int x = 0; x < n; ++x) d[x] = std::min(d[x], 80.0f);
    for (int x = 0; x < n; ++x) {
        const float wt = expNeg(d[x]);
        d[x] = wt;
        w[x] += wt;
        a0[x] += wt * v0[x];
        a1[x] += wt * v1[x];
        a2[x] += wt * v2[x];
    }
}

void accumulateSquared(int n, const float* __restrict w, float* __restrict b0, float* __restrict b1,
                       float* __restrict b2, const float* __restrict v0, const float* __restrict v1,
                       const float* __restrict v2) {
    for (int x = 0; x < n; ++x) {
        const float w2 = w[x] * w[x];
        b0[x] += w2 * v0[x];
        b1[x] += w2 * v1[x];
        b2[x] += w2 * v2[x];
    }
}

// The first-order sums of one row of offsets (dy fixed), for the offset dx (ox over the
// radius) of every pixel in the row: the weight times ox, times ox^2 and times the values.
void accumulateRowFirstOrder(int n, const float* __restrict w, float ox, float* __restrict sx,
                             float* __restrict sxx, float* __restrict x0, float* __restrict x1,
                             float* __restrict x2, const float* __restrict v0,
                             const float* __restrict v1, const float* __restrict v2) {
    for (int x = 0; x < n; ++x) {
        const float wx = w[x] * ox;
        sx[x] += wx;
        sxx[x] += wx * ox;
        x0[x] += wx * v0[x];
        x1[x] += wx * v1[x];
        x2[x] += wx * v2[x];
    }
}

// Adds a row of offsets' sums (dy fixed: oy over the radius) to the window's, and clears them:
// the moments in y follow from the row's sums times oy, so the loop over the offsets keeps
// 9 sums per pixel instead of 15.
void addRowSums(size_t n, float oy, TileScratch& s) {
    float* __restrict w = s.acc[kRowW].data();
    float* __restrict wx = s.acc[kRowX].data();
    float* __restrict wxx = s.acc[kRowXX].data();
    float* __restrict sw = s.acc[kW].data();
    float* __restrict sx = s.acc[kX].data();
    float* __restrict sy = s.acc[kY].data();
    float* __restrict sxx = s.acc[kXX].data();
    float* __restrict sxy = s.acc[kXY].data();
    float* __restrict syy = s.acc[kYY].data();
    for (size_t i = 0; i < n; ++i) {
        sw[i] += w[i];
        sx[i] += wx[i];
        sy[i] += oy * w[i];
        sxx[i] += wxx[i];
        sxy[i] += oy * wx[i];
        syy[i] += oy * oy * w[i];
    }
    for (int c = 0; c < 3; ++c) {
        float* __restrict v = s.acc[kRowV + c].data();
        float* __restrict xv = s.acc[kRowXV + c].data();
        float* __restrict sv = s.acc[kV + c].data();
        float* __restrict sxv = s.acc[kXV + c].data();
        float* __restrict syv = s.acc[kYV + c].data();
        for (size_t i = 0; i < n; ++i) {
            sv[i] += v[i];
            sxv[i] += xv[i];
            syv[i] += oy * v[i];
        }
    }
    for (int a = kRowW; a < kSumCount; ++a) std::fill(s.acc[a].begin(), s.acc[a].end(), 0.0f);
}

// The value at the window's centre of the weighted least-squares plane through the values, per
// channel, from pixel i's sums; the slopes' ridge keeps it near the weighted mean where the
// weights do not pin a plane down (a thin line of similar pixels). In double: the 3x3 system's
// cofactors cancel.
void solvePlane(const TileScratch& s, size_t i, float ridge, float out[3], float& leverage) {
    const double a00 = s.acc[kW][i], a01 = s.acc[kX][i], a02 = s.acc[kY][i];
    const double a11 = s.acc[kXX][i] + ridge * a00, a12 = s.acc[kXY][i];
    const double a22 = s.acc[kYY][i] + ridge * a00;
    // The first row of the inverse: the cofactors of the first column over the determinant.
    const double c0 = a11 * a22 - a12 * a12, c1 = a02 * a12 - a01 * a22, c2 = a01 * a12 - a02 * a11;
    const double det = a00 * c0 + a01 * c1 + a02 * c2;
    if (!(det > 1e-12 * a00 * a00 * a00)) {
        for (int c = 0; c < 3; ++c) out[c] = static_cast<float>(s.acc[kV + c][i] / a00);
        leverage = static_cast<float>(1.0 / a00);
        return;
    }
    for (int c = 0; c < 3; ++c)
        out[c] = static_cast<float>(
            (c0 * s.acc[kV + c][i] + c1 * s.acc[kXV + c][i] + c2 * s.acc[kYV + c][i]) / det);
    leverage = static_cast<float>(c0 / det);  // the centre's weight is 1
}

void filterTile(const NlMeansGuide& g, const std::array<const Plane*, 3>& values,
                const NlMeansParams& p, const Tile& t, const std::array<const Plane*, 3>* vv,
                const std::vector<uint8_t>* exact, TileScratch& s, const NlMeansOutputs& out) {
    const int width = g.color[0]->width(), height = g.color[0]->height();
    const int f = p.patch, tw = t.x1 - t.x0, th = t.y1 - t.y0;
    // Pixels that keep their values (NlMeansParams::keepExact): a tile of them only, directly.
    auto keep = [&](int x, int y) {
        for (int c = 0; c < 3; ++c) {
            out.value[c]->at(x, y) = values[c]->at(x, y);
            if (out.variance[0]) out.variance[c]->at(x, y) = 0.0f;
        }
    };
    if (exact) {
        bool all = true;
        for (int y = t.y0; all && y < t.y1; ++y)
            for (int x = t.x0; x < t.x1; ++x)
                all = all && (*exact)[static_cast<size_t>(y) * width + x];
        if (all) {
            for (int y = t.y0; y < t.y1; ++y)
                for (int x = t.x0; x < t.x1; ++x) keep(x, y);
            return;
        }
    }
    const int dw = tw + 2 * f;  // distance rows: tile columns grown by the patch
    const size_t tileSize = static_cast<size_t>(tw) * th;
    s.distance.assign(static_cast<size_t>(dw) * (th + 2 * f), 0.0f);
    s.rowSum.assign(static_cast<size_t>(tw) * (th + 2 * f), 0.0f);
    s.total.assign(static_cast<size_t>(tw), 0.0f);
    for (int a = 0; a < kSumCount; ++a) {
        const bool used = a < kVar || (a < kX ? vv != nullptr : p.firstOrder);
        // (kW and kV are always summed: directly, or for a first-order fit through addRowSums.)
        if (used) s.acc[a].assign(tileSize, 0.0f);
    }
    const float offsetScale = 1.0f / static_cast<float>(std::max(1, p.radius));

    const float k2 = p.k * p.k;
    const float patchNorm = 1.0f / static_cast<float>(3 * (2 * f + 1) * (2 * f + 1));
    const bool useNormal = g.normal[0] && p.normalWeight > 0;
    const bool useAlbedo = g.albedo[0] && p.albedoWeight > 0;
    const bool useDepth = g.depth && p.depthWeight > 0;

    for (int dy = -p.radius; dy <= p.radius; ++dy) {
        // Rows of p whose q = p + (dx, dy) lies in the image.
        const int ya = std::max(t.y0, -dy), yb = std::min(t.y1, height - dy);
        if (ya >= yb) continue;
        for (int dx = -p.radius; dx <= p.radius; ++dx) {
            const int xa = std::max(t.x0, -dx), xb = std::min(t.x1, width - dx);
            if (xa >= xb) continue;
            const int n = xb - xa;
            // Per-pixel colour distance over the rows and columns the patches cover; p and q
            // both lie in the image, so their patches stay within the planes' borders.
            for (int y = ya - f; y < yb + f; ++y) {
                float* d = s.distance.data() + static_cast<size_t>(y - t.y0 + f) * dw +
                           (xa - f - t.x0 + f);
                const int x = xa - f;
                colourDistance(n + 2 * f, d, g.color[0]->row(y) + x, g.color[1]->row(y) + x,
                               g.color[2]->row(y) + x, g.color[0]->row(y + dy) + x + dx,
                               g.color[1]->row(y + dy) + x + dx, g.color[2]->row(y + dy) + x + dx,
                               g.variance[0]->row(y) + x, g.variance[1]->row(y) + x,
                               g.variance[2]->row(y) + x, g.variance[0]->row(y + dy) + x + dx,
                               g.variance[1]->row(y + dy) + x + dx,
                               g.variance[2]->row(y + dy) + x + dx, p.alpha, k2);
                patchSums(f, n,
                          s.rowSum.data() + static_cast<size_t>(y - t.y0 + f) * tw + (xa - t.x0),
                          d + f);
            }
            for (int y = ya; y < yb; ++y) {
                const size_t o = static_cast<size_t>(y - t.y0) * tw + (xa - t.x0);
                const float* rows[7];
                for (int j = -f; j <= f; ++j)
                    rows[j + f] =
                        s.rowSum.data() + static_cast<size_t>(y + j - t.y0 + f) * tw + (xa - t.x0);
                float* dist = s.total.data();
                patchColumns(f, n, dist, rows, patchNorm);
                const int qx = xa + dx, qy = y + dy;
                if (useNormal)
                    addVectorDistance(n, dist, g.normal[0]->row(y) + xa, g.normal[1]->row(y) + xa,
                                      g.normal[2]->row(y) + xa, g.normal[0]->row(qy) + qx,
                                      g.normal[1]->row(qy) + qx, g.normal[2]->row(qy) + qx,
                                      p.normalWeight);
                if (useAlbedo)
                    addVectorDistance(n, dist, g.albedo[0]->row(y) + xa, g.albedo[1]->row(y) + xa,
                                      g.albedo[2]->row(y) + xa, g.albedo[0]->row(qy) + qx,
                                      g.albedo[1]->row(qy) + qx, g.albedo[2]->row(qy) + qx,
                                      p.albedoWeight);
                if (useDepth)
                    addDepthDistance(n, dist, g.depth->row(y) + xa, g.depth->row(qy) + qx,
                                     g.depthDx->row(y) + xa, g.depthDy->row(y) + xa,
                                     static_cast<float>(dx), static_cast<float>(dy), p.depthWeight);
                auto sum = [&](int a) { return s.acc[a].data() + o; };
                // A first-order fit sums a row of offsets first (addRowSums).
                const int w0 = p.firstOrder ? kRowW : kW, v0 = p.firstOrder ? kRowV : kV;
                accumulate(n, dist, sum(w0), sum(v0), sum(v0 + 1), sum(v0 + 2),
                           values[0]->row(qy) + qx, values[1]->row(qy) + qx,
                           values[2]->row(qy) + qx);
                if (p.firstOrder)
                    accumulateRowFirstOrder(n, dist, static_cast<float>(dx) * offsetScale,
                                            sum(kRowX), sum(kRowXX), sum(kRowXV), sum(kRowXV + 1),
                                            sum(kRowXV + 2), values[0]->row(qy) + qx,
                                            values[1]->row(qy) + qx, values[2]->row(qy) + qx);
                if (vv)
                    accumulateSquared(n, dist, sum(kVar), sum(kVar + 1), sum(kVar + 2),
                                      (*vv)[0]->row(qy) + qx, (*vv)[1]->row(qy) + qx,
                                      (*vv)[2]->row(qy) + qx);
            }
        }
        if (p.firstOrder) addRowSums(tileSize, static_cast<float>(dy) * offsetScale, s);
    }
    for (int y = t.y0; y < t.y1; ++y)
        for (int x = t.x0; x < t.x1; ++x) {
            const size_t i = static_cast<size_t>(y - t.y0) * tw + (x - t.x0);
            const float inv = 1.0f / s.acc[kW][i];  // the centre's own weight is 1: never 0
            float fit[3], leverage = inv;
            if (p.firstOrder) {
                solvePlane(s, i, p.ridge, fit, leverage);
            } else {
                for (int c = 0; c < 3; ++c) fit[c] = s.acc[kV + c][i] * inv;
            }
            for (int c = 0; c < 3; ++c) out.value[c]->at(x, y) = fit[c];
            // The weighted mean's variance; a fit's is larger by about the ratio of their
            // leverages (exactly so for equal weights and variances), most where it extrapolates.
            if (out.variance[0])
                for (int c = 0; c < 3; ++c)
                    out.variance[c]->at(x, y) = s.acc[kVar + c][i] * inv * leverage;
            if (exact && (*exact)[static_cast<size_t>(y) * width + x]) keep(x, y);
        }
}

}  // namespace

void nlMeans(const NlMeansGuide& guide, const std::array<const Plane*, 3>& values,
             const NlMeansParams& params, const NlMeansOutputs& out,
             const std::array<const Plane*, 3>* valueVariance, ThreadPool& pool) {
    const int width = guide.color[0]->width(), height = guide.color[0]->height();
    const int tilesX = (width + kTileWidth - 1) / kTileWidth;
    const int tilesY = (height + kTileHeight - 1) / kTileHeight;
    NlMeansParams p = params;
    p.patch = std::clamp(p.patch, 0, 3);
    // keepExact: which pixels have no guide variance within their window's reach (a pixel's
    // own decision, whatever the tiling).
    std::vector<uint8_t> exact;
    if (p.keepExact) {
        const int reach = p.radius + p.patch;
        const size_t n = static_cast<size_t>(width) * height;
        std::vector<uint8_t> rows(n);  // no variance within reach along the row
        exact.resize(n);
        for (int y = 0; y < height; ++y) {
            const float* v[3] = {guide.variance[0]->row(y), guide.variance[1]->row(y),
                                 guide.variance[2]->row(y)};
            int last = -(1 << 30);  // the last column with variance
            std::vector<int> next(static_cast<size_t>(width) + 1, 1 << 30);
            for (int x = width - 1; x >= 0; --x)
                next[x] = v[0][x] != 0 || v[1][x] != 0 || v[2][x] != 0 ? x : next[x + 1];
            for (int x = 0; x < width; ++x) {
                if (v[0][x] != 0 || v[1][x] != 0 || v[2][x] != 0) last = x;
                rows[static_cast<size_t>(y) * width + x] = x - last > reach && next[x] - x > reach;
            }
        }
        for (int x = 0; x < width; ++x) {
            int last = -(1 << 30);
            std::vector<int> next(static_cast<size_t>(height) + 1, 1 << 30);
            for (int y = height - 1; y >= 0; --y)
                next[y] = rows[static_cast<size_t>(y) * width + x] ? next[y + 1] : y;
            for (int y = 0; y < height; ++y) {
                if (!rows[static_cast<size_t>(y) * width + x]) last = y;
                exact[static_cast<size_t>(y) * width + x] = y - last > reach && next[y] - y > reach;
            }
        }
    }
    parallelFor(pool, 0, static_cast<size_t>(tilesX) * tilesY, 1, [&](size_t first, size_t last) {
        TileScratch scratch;
        for (size_t i = first; i < last; ++i) {
            const int tx = static_cast<int>(i % tilesX), ty = static_cast<int>(i / tilesX);
            Tile t{tx * kTileWidth, std::min(width, (tx + 1) * kTileWidth), ty * kTileHeight,
                   std::min(height, (ty + 1) * kTileHeight)};
            filterTile(guide, values, p, t, out.variance[0] ? valueVariance : nullptr,
                       exact.empty() ? nullptr : &exact, scratch, out);
        }
    });
}

}  // namespace glint::denoise_detail
