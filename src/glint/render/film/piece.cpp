#include "glint/render/film/piece.h"

#include <algorithm>
#include <charconv>
#include <cinttypes>
#include <climits>
#include <cstdio>
#include <map>
#include <tuple>

namespace glint {

namespace {

/// Tile rows overlapping [y0, y1) that belong to the piece, as pixel rows: calls f(ya, yb) for
/// each run of rows the piece holds.
template <typename F>
void forEachRowRun(const PieceInfo& p, F&& f) {
    const PixelBounds& c = p.crop;
    if (c.empty()) return;
    if (p.parts <= 1) {
        f(c.y0, c.y1);
        return;
    }
    const int tile = std::max(p.tileSize, 1);
    for (int row = c.y0 / tile; row * tile < c.y1; ++row)
        if (row % p.parts == p.part)
            f(std::max(row * tile, c.y0), std::min((row + 1) * tile, c.y1));
}

std::string hex64(uint64_t v) {
    char buf[20];
    std::snprintf(buf, sizeof buf, "%016" PRIx64, v);
    return buf;
}

/// The value of `key` in "key=value key=value" settings, or "(none)".
std::string settingValue(const std::string& settings, const std::string& key) {
    size_t pos = 0;
    while (pos < settings.size()) {
        size_t end = settings.find(' ', pos);
        if (end == std::string::npos) end = settings.size();
        std::string word = settings.substr(pos, end - pos);
        if (word.compare(0, key.size() + 1, key + "=") == 0) return word.substr(key.size() + 1);
        pos = end + 1;
    }
    return "(none)";
}

/// The first setting whose value differs, as "key=a" and "key=b".
std::pair<std::string, std::string> firstDifference(const std::string& a, const std::string& b) {
    std::vector<std::string> keys;
    for (const std::string* s : {&a, &b}) {
        size_t pos = 0;
        while (pos < s->size()) {
            size_t end = s->find(' ', pos);
            if (end == std::string::npos) end = s->size();
            std::string word = s->substr(pos, end - pos);
            keys.push_back(word.substr(0, word.find('=')));
            pos = end + 1;
        }
    }
    for (const std::string& k : keys) {
        std::string va = settingValue(a, k), vb = settingValue(b, k);
        if (va != vb) return {k + "=" + va, k + "=" + vb};
    }
    return {"settings '" + a + "'", "settings '" + b + "'"};
}

std::string adaptiveText(const PieceInfo& p) {
    if (!(p.noiseThreshold > 0)) return "a fixed number of samples per pixel";
    char buf[96];
    std::snprintf(buf, sizeof buf, "adaptive sampling to noise %g from %d samples",
                  p.noiseThreshold, p.minSpp);
    return buf;
}

std::string passesText(const PieceInfo& p) {
    return p.aovs.any() ? "passes " + aovListText(p.aovs) : std::string("no render passes");
}

/// Problems that pieces of other frames have, against the first piece.
void checkBelongTogether(const std::vector<PieceInfo>& pieces,
                         const std::vector<std::string>& files, std::vector<PieceProblem>& out) {
    const PieceInfo& f = pieces[0];
    const std::string& first = files[0];
    for (size_t i = 1; i < pieces.size(); ++i) {
        const PieceInfo& p = pieces[i];
        auto add = [&](const std::string& what) {
            out.push_back({files[i], what + ": pieces of one frame must agree"});
        };
        if (p.width != f.width || p.height != f.height)
            add("a " + std::to_string(p.width) + "x" + std::to_string(p.height) + " frame, but " +
                first + " is " + std::to_string(f.width) + "x" + std::to_string(f.height));
        if (p.spp != f.spp)
            add(std::to_string(p.spp) + " samples per pixel, but " + first + " has " +
                std::to_string(f.spp));
        if (p.seed != f.seed)
            add("seed " + std::to_string(p.seed) + ", but " + first + " has seed " +
                std::to_string(f.seed));
        if (p.sceneHash != f.sceneHash)
            add("scene hash " + hex64(p.sceneHash) + ", but " + first + " has " +
                hex64(f.sceneHash) +
                " (rendered from different scene files, or meshes and textures they load)");
        if (p.settings != f.settings) {
            auto [mine, theirs] = firstDifference(p.settings, f.settings);
            add(mine + ", but " + first + " has " + theirs);
        }
        if (p.noiseThreshold != f.noiseThreshold || p.minSpp != f.minSpp)
            add(adaptiveText(p) + ", but " + first + " has " + adaptiveText(f));
        if (p.aovs != f.aovs) add(passesText(p) + ", but " + first + " has " + passesText(f));
        if (p.version != f.version)
            add("rendered by glint " + p.version + ", but " + first + " by glint " + f.version);
    }
}

/// Pixels with one problem: as rectangles where they arrive in rows (each piece's pixels, and
/// the final scan, go top to bottom, left to right), and their bounding box and count.
class Region {
  public:
    void add(int x, int y) {
        if (count_++ == 0) box_ = {x, x, y, y};
        box_ = {std::min(box_.x0, x), std::max(box_.x1, x), std::min(box_.y0, y),
                std::max(box_.y1, y)};
        if (open_ && y == run_.y0 && x == run_.x1 + 1) {
            run_.x1 = x;
            return;
        }
        close();
        run_ = {x, x, y, y};
        open_ = true;
    }
    int top() const { return box_.y0; }
    int left() const { return box_.x0; }
    long long count() const { return count_; }

    /// "pixel (3,4)", "pixels (0,16)-(639,31)", "pixels (0,0)-(2,9) and (7,0)-(9,9)", or
    /// "1200 pixels within (0,16)-(639,479)".
    std::string str() {
        close();
        if (count_ == 1) return "pixel " + pt(box_.x0, box_.y0);
        if (!overflow_ && rects_.size() <= 3) {
            std::string s = "pixels " + rect(rects_[0]);
            for (size_t i = 1; i < rects_.size(); ++i)
                s += (i + 1 == rects_.size() ? " and " : ", ") + rect(rects_[i]);
            return s;
        }
        return std::to_string(count_) + " pixels within " + rect(box_);
    }

  private:
    struct Rect {
        int x0, x1, y0, y1;  // inclusive
    };
    static std::string pt(int x, int y) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "(%d,%d)", x, y);
        return buf;
    }
    static std::string rect(const Rect& r) {
        return r.x0 == r.x1 && r.y0 == r.y1 ? pt(r.x0, r.y0)
                                            : pt(r.x0, r.y0) + "-" + pt(r.x1, r.y1);
    }
    /// Ends the run of the current row: it extends the rectangle above it of the same columns,
    /// or starts one.
    void close() {
        if (!open_) return;
        open_ = false;
        for (Rect& r : rects_)
            if (r.x0 == run_.x0 && r.x1 == run_.x1 && r.y1 + 1 == run_.y0) {
                r.y1 = run_.y0;
                return;
            }
        if (rects_.size() >= kMaxRects) {
            overflow_ = true;
            return;
        }
        rects_.push_back(run_);
    }
    static constexpr size_t kMaxRects = 64;
    Rect box_{0, -1, 0, -1}, run_{0, -1, 0, -1};
    long long count_ = 0;
    bool open_ = false, overflow_ = false;
    std::vector<Rect> rects_;
};

std::string range(int a, int b) { return std::to_string(a) + ":" + std::to_string(b); }

/// Splits `text` at `sep` into exactly `n` non-negative integers below 2^31.
bool splitInts(std::string_view text, char sep, size_t n, int* out) {
    if (static_cast<size_t>(std::count(text.begin(), text.end(), sep)) != n - 1) return false;
    const char* p = text.data();
    const char* end = text.data() + text.size();
    for (size_t k = 0; k < n; ++k) {
        const char* stop = std::find(p, end, sep);
        long long v = -1;
        auto [q, ec] = std::from_chars(p, stop, v);
        if (p == stop || ec != std::errc() || q != stop || v < 0 || v > INT_MAX) return false;
        out[k] = static_cast<int>(v);
        p = stop == end ? end : stop + 1;
    }
    return true;
}

}  // namespace

PixelBounds PieceInfo::bounds() const {
    PixelBounds b;
    bool any = false;
    forEachRowRun(*this, [&](int ya, int yb) {
        if (!any) b = {crop.x0, crop.x1, ya, yb};
        b.y1 = yb;
        any = true;
    });
    return any ? b : PixelBounds{};
}

long long PieceInfo::pixelCount() const {
    long long rows = 0;
    forEachRowRun(*this, [&](int ya, int yb) { rows += yb - ya; });
    return rows * std::max(crop.x1 - crop.x0, 0);
}

std::string formatCrop(const PixelBounds& b) {
    return std::to_string(b.x0) + "," + std::to_string(b.x1) + "," + std::to_string(b.y0) + "," +
           std::to_string(b.y1);
}

std::string PieceInfo::describe() const {
    std::vector<std::string> words;
    if (parts > 1) words.push_back("part " + std::to_string(part) + "/" + std::to_string(parts));
    if (!(crop == PixelBounds{0, width, 0, height})) words.push_back("crop " + formatCrop(crop));
    if (sampleBegin != 0 || sampleEnd != spp)
        words.push_back("samples " + range(sampleBegin, sampleEnd));
    if (words.empty()) return "the whole frame";
    std::string s = words[0];
    for (size_t i = 1; i < words.size(); ++i) s += ", " + words[i];
    return s;
}

std::string parseCrop(std::string_view text, PixelBounds& out) {
    int v[4];
    if (!splitInts(text, ',', 4, v))
        return "expected x0,x1,y0,y1 (four pixel bounds, the upper ones excluded), got '" +
               std::string(text) + "'";
    if (v[0] >= v[1] || v[2] >= v[3])
        return "'" + std::string(text) +
               "' is empty: x0 < x1 and y0 < y1 are needed (pixels x0 to x1-1, y0 to y1-1)";
    out = {v[0], v[1], v[2], v[3]};
    return {};
}

std::string parsePart(std::string_view text, int& part, int& parts) {
    int v[2];
    if (!splitInts(text, '/', 2, v))
        return "expected K/N (piece K of N, from 0), got '" + std::string(text) + "'";
    if (v[1] < 1 || v[1] > kMaxParts)
        return "N must be 1 to " + std::to_string(kMaxParts) + ", got '" + std::string(text) + "'";
    if (v[0] >= v[1]) return "K must be 0 to N-1, got '" + std::string(text) + "'";
    part = v[0];
    parts = v[1];
    return {};
}

std::string parseSampleRange(std::string_view text, int& begin, int& end) {
    int v[2];
    if (!splitInts(text, ':', 2, v))
        return "expected A:B (samples A to B-1), got '" + std::string(text) + "'";
    if (v[0] >= v[1]) return "A:B needs A < B, got '" + std::string(text) + "'";
    begin = v[0];
    end = v[1];
    return {};
}

bool mergesBefore(const PieceInfo& a, const PieceInfo& b) {
    auto key = [](const PieceInfo& p) {
        return std::tuple(p.sampleBegin, p.sampleEnd, p.parts, p.part, p.tileSize, p.crop.y0,
                          p.crop.x0, p.crop.y1, p.crop.x1);
    };
    return key(a) < key(b);
}

std::vector<PieceProblem> checkPieces(const std::vector<PieceInfo>& pieces,
                                      const std::vector<std::string>& files, size_t limit) {
    std::vector<PieceProblem> problems;
    if (pieces.empty()) return {{"", "no pieces to merge"}};
    checkBelongTogether(pieces, files, problems);
    if (!problems.empty()) return problems;  // coverage means nothing across frames

    // Pieces given twice: named as such, then left out of the pixel check.
    std::vector<size_t> order(pieces.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return mergesBefore(pieces[a], pieces[b]); });
    std::vector<size_t> used;
    for (size_t k = 0; k < order.size(); ++k) {
        const size_t i = order[k];
        if (!used.empty() && pieces[used.back()].sameRegion(pieces[i])) {
            problems.push_back({files[i], pieces[i].describe() + " given twice: " +
                                              files[used.back()] + " and " + files[i]});
            continue;
        }
        used.push_back(i);
    }

    // Per pixel, the next sample expected and the piece that covered the samples before it.
    // Pieces go in merge order, so each pixel's ranges arrive sorted by their first sample:
    // they partition [0, spp) exactly when each starts where the one before ended.
    const PieceInfo& frame = pieces[0];
    const int w = frame.width, h = frame.height, spp = frame.spp;
    const size_t n = static_cast<size_t>(w) * static_cast<size_t>(h);
    std::vector<int32_t> next(n, 0), last(n, -1);

    // Pixels with a problem, grouped by what the problem is. With parts N > 1 common to every
    // piece (and the crop too), missing samples are also grouped by part, to name the part.
    bool commonParts = frame.parts > 1;
    for (const PieceInfo& p : pieces)
        commonParts = commonParts && p.parts == frame.parts && p.tileSize == frame.tileSize &&
                      p.crop == frame.crop;
    struct Key {
        int kind;  // 0: missing samples [a, b); 1: samples [a, b) also in piece `other`
        int a, b;
        int32_t other, piece;
        int partIndex;
        bool operator<(const Key& o) const {
            return std::tie(kind, a, b, other, piece, partIndex) <
                   std::tie(o.kind, o.a, o.b, o.other, o.piece, o.partIndex);
        }
    };
    std::map<Key, Region> groups;
    constexpr size_t kMaxGroups = 100000;  // bounds the memory for pathological sets
    auto note = [&](Key key, int x, int y) {
        auto it = groups.find(key);
        if (it == groups.end()) {
            if (groups.size() >= kMaxGroups) return;
            it = groups.emplace(key, Region{}).first;
        }
        it->second.add(x, y);
    };
    auto partOf = [&](int y) { return commonParts ? (y / frame.tileSize) % frame.parts : -1; };

    for (size_t i : used) {
        const PieceInfo& p = pieces[i];
        const int32_t pi = static_cast<int32_t>(i);
        const PixelBounds b = p.bounds();
        for (int y = b.y0; y < b.y1; ++y) {
            if (!p.covers(b.x0, y)) continue;  // rows of other parts
            for (int x = b.x0; x < b.x1; ++x) {
                const size_t at = static_cast<size_t>(y) * static_cast<size_t>(w) + x;
                if (next[at] < p.sampleBegin)
                    note({0, next[at], p.sampleBegin, -1, -1, partOf(y)}, x, y);
                else if (next[at] > p.sampleBegin)
                    note({1, p.sampleBegin, std::min(next[at], p.sampleEnd), last[at], pi, -1}, x,
                         y);
                next[at] = std::max(next[at], p.sampleEnd);
                last[at] = pi;
            }
        }
    }
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t at = static_cast<size_t>(y) * static_cast<size_t>(w) + x;
            if (next[at] < spp) note({0, next[at], spp, -1, -1, partOf(y)}, x, y);
        }

    // The problems, top to bottom.
    std::vector<std::pair<const Key*, Region*>> sorted;
    for (auto& [key, region] : groups) sorted.emplace_back(&key, &region);
    std::stable_sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) {
        return std::pair(a.second->top(), a.second->left()) <
               std::pair(b.second->top(), b.second->left());
    });
    for (const auto& [key, region] : sorted) {
        const std::string samples = "samples " + range(key->a, key->b);
        if (key->kind == 1) {
            problems.push_back({files[static_cast<size_t>(key->piece)],
                                samples + " of " + region->str() + " are also in " +
                                    files[static_cast<size_t>(key->other)] + " (" +
                                    pieces[static_cast<size_t>(key->other)].describe() + ")"});
            continue;
        }
        if (key->partIndex >= 0) {
            PieceInfo whole = frame;
            whole.part = key->partIndex;
            if (whole.pixelCount() == region->count()) {
                problems.push_back({"", "part " + std::to_string(key->partIndex) + "/" +
                                            std::to_string(frame.parts) +
                                            " is missing: no piece covers " + samples + " of its " +
                                            std::to_string(region->count()) + " pixels"});
                continue;
            }
        }
        problems.push_back({"", region->str() + ": no piece covers " + samples});
    }
    if (groups.size() >= kMaxGroups) problems.push_back({"", "(and more problems, not listed)"});

    if (problems.size() > limit) {
        const size_t more = problems.size() - limit;
        problems.resize(limit);
        problems.push_back(
            {"", "and " + std::to_string(more) + " more problem" + (more == 1 ? "" : "s")});
    }
    return problems;
}

}  // namespace glint
