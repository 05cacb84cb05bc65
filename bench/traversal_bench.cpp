// Glint's BVH next to Intel Embree 3, measured in the same run (issue 3, "Build", items 1 and 2).
//
//  1. Build: the rippled torus + ground of bench/torus.h and the scene7 dragon, Glint's build on
//     1 and 2 threads against Embree's MEDIUM build on devices made with "threads=1" and
//     "threads=2"; Mtris/s and bytes per triangle.
//  2. Traversal on the torus, 1 and 2 threads, identical float rays for both: primary rays of
//     the camera, shadow rays to its light, 2M random rays (closest and any hit), and the
//     primary rays in 8-ray packets. Mrays/s, the ratio Glint/Embree and the goal, plus
//     how often the two agree on the result.
//
// Every figure is a median of --runs repetitions; Glint and Embree alternate within each
// repetition, so load from other processes on the machine affects both alike. All rays are built
// before anything is timed. The program uses only Glint's public Bvh API.
//
// Usage: glint_traversal_bench [--runs N] [--quick] [--build-only] [--embree-isa ISA]
//                              [--scene7 FILE]

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpedantic"
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <embree3/rtcore.h>
#pragma GCC diagnostic pop

#include "glint/accel/bvh.h"
#include "glint/core/parallel.h"
#include "glint/core/ray.h"
#include "glint/geometry/primitives.h"
#include "glint/io/course/course_loader.h"
#include "torus.h"

namespace {

using glint::Vec3;
using Clock = std::chrono::steady_clock;

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr std::array<int, 2> kThreadCounts{1, 2};

// ---------------------------------------------------------------------------------------------
// Command line

struct Options {
    int runs = 5;
    bool quick = false;
    bool buildOnly = false;  ///< Measure the builds only (section 1).
    std::string embreeIsa;   ///< Empty: Embree picks its widest ISA for the CPU.
    std::string scene7 = (std::filesystem::path(__FILE__).parent_path().parent_path() /
                          "tests/data/cse167x/scene7.test")
                             .string();
};

void usage(std::FILE* out) {
    std::fprintf(out,
                 "Usage: glint_traversal_bench [options]\n"
                 "Glint's BVH against Embree 3 (build, memory, traversal), same run.\n"
                 "  --runs N          repetitions per figure, median reported (default 5)\n"
                 "  --quick           smoke test: 200x100 torus, 320x180 image, 200k random "
                 "rays, 2 runs\n"
                 "  --build-only      measure the builds only, not traversal\n"
                 "  --embree-isa ISA  cap Embree's ISA (sse2, sse4.2, avx, avx2, avx512); default: "
                 "its widest\n"
                 "  --scene7 FILE     the dragon scene (default: tests/data/cse167x/scene7.test)\n"
                 "  -h, --help\n");
}

Options parseOptions(int argc, char** argv) {
    Options o;
    bool runsGiven = false;
    auto fail = [](const std::string& message) {
        std::fprintf(stderr, "glint_traversal_bench: %s\n", message.c_str());
        usage(stderr);
        std::exit(2);
    };
    for (int i = 1; i < argc; ++i) {
        std::string_view arg = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) fail(std::string(arg) + " needs a value");
            return argv[++i];
        };
        if (arg == "-h" || arg == "--help") {
            usage(stdout);
            std::exit(0);
        } else if (arg == "--quick") {
            o.quick = true;
        } else if (arg == "--build-only") {
            o.buildOnly = true;
        } else if (arg == "--runs") {
            std::string v = value();
            char* end = nullptr;
            long n = std::strtol(v.c_str(), &end, 10);
            if (end == v.c_str() || *end != '\0' || n < 1 || n > 1000)
                fail("--runs wants an integer from 1 to 1000, not '" + v + "'");
            o.runs = static_cast<int>(n);
            runsGiven = true;
        } else if (arg == "--embree-isa") {
            o.embreeIsa = value();
            // Embree quietly falls back to SSE2 for a name it does not know.
            constexpr std::array<std::string_view, 5> known{"sse2", "sse4.2", "avx", "avx2",
                                                            "avx512"};
            if (std::find(known.begin(), known.end(), o.embreeIsa) == known.end())
                fail("--embree-isa wants sse2, sse4.2, avx, avx2 or avx512, not '" + o.embreeIsa +
                     "'");
        } else if (arg == "--scene7") {
            o.scene7 = value();
        } else {
            fail("unknown option '" + std::string(arg) + "'");
        }
    }
    if (o.quick && !runsGiven) o.runs = 2;
    return o;
}

// ---------------------------------------------------------------------------------------------
// Small helpers

double secondsSince(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string withCommas(uint64_t n) {
    std::string digits = std::to_string(n), out;
    for (size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
        out += digits[i];
    }
    return out;
}

void progress(const std::string& what) {
    std::fprintf(stderr, "  ... %s\n", what.c_str());
    std::fflush(stderr);
}

/// The 1-minute load average, or -1 if unknown.
double loadAverage() {
    std::ifstream in("/proc/loadavg");
    double load = -1;
    in >> load;
    return load;
}

std::string cpuName() {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("model name", 0) == 0) {
            size_t colon = line.find(':');
            if (colon != std::string::npos && colon + 2 <= line.size())
                return line.substr(colon + 2);
        }
    return "unknown CPU";
}

/// Runs `body(begin, end)` over [0, count) in chunks handed out by an atomic counter to
/// `threads` workers (the calling thread is one of them). Returns the sum of what body returns
/// (hit counts, which also keep the work from being optimised away).
template <typename Body>
uint64_t parallelChunks(int threads, size_t count, size_t chunk, const Body& body) {
    std::atomic<size_t> next{0};
    std::atomic<uint64_t> total{0};
    auto work = [&] {
        uint64_t sum = 0;
        for (;;) {
            size_t begin = next.fetch_add(chunk, std::memory_order_relaxed);
            if (begin >= count) break;
            sum += body(begin, std::min(begin + chunk, count));
        }
        total.fetch_add(sum, std::memory_order_relaxed);
    };
    std::vector<std::thread> workers;
    for (int i = 1; i < threads; ++i) workers.emplace_back(work);
    work();
    for (std::thread& w : workers) w.join();
    return total.load();
}

// ---------------------------------------------------------------------------------------------
// Embree

[[noreturn]] void embreeFailed(const char* what, RTCError code) {
    std::fprintf(stderr, "glint_traversal_bench: Embree error %d: %s\n", static_cast<int>(code),
                 what ? what : "");
    std::exit(1);
}

void onEmbreeError(void*, RTCError code, const char* message) { embreeFailed(message, code); }

/// Bytes an Embree device holds, as its memory monitor reports them.
struct MemoryCounter {
    std::atomic<long long> bytes{0};
};

bool onEmbreeMemory(void* user, ssize_t bytes, bool /*post*/) {
    static_cast<MemoryCounter*>(user)->bytes.fetch_add(bytes, std::memory_order_relaxed);
    return true;
}

/// An Embree device with a fixed number of build threads and a memory monitor. Scenes made with
/// it must be released before it is destroyed.
class EmbreeDevice {
  public:
    EmbreeDevice(int threads, const std::string& isa) {
        std::string config = "threads=" + std::to_string(threads);
        if (!isa.empty()) config += ",max_isa=" + isa;
        device_ = rtcNewDevice(config.c_str());
        if (!device_) embreeFailed(config.c_str(), rtcGetDeviceError(nullptr));
        rtcSetDeviceErrorFunction(device_, onEmbreeError, nullptr);
        rtcSetDeviceMemoryMonitorFunction(device_, onEmbreeMemory, &memory_);
    }
    ~EmbreeDevice() { rtcReleaseDevice(device_); }
    EmbreeDevice(const EmbreeDevice&) = delete;
    EmbreeDevice& operator=(const EmbreeDevice&) = delete;

    RTCDevice get() const { return device_; }
    long long bytes() const { return memory_.bytes.load(); }

  private:
    RTCDevice device_ = nullptr;
    MemoryCounter memory_;
};

using EmbreeScene = std::unique_ptr<RTCSceneTy, void (*)(RTCScene)>;

/// Triangles as Embree reads them: float xyz vertices and uint32 index triples, owned by the
/// application and shared with Embree (so they are not part of Embree's memory figure).
struct SharedMesh {
    std::vector<float> vertices;  ///< x, y, z per vertex, plus one float of padding at the end.
    std::vector<uint32_t> indices;

    size_t vertexCount() const { return (vertices.size() - 1) / 3; }
    size_t triangleCount() const { return indices.size() / 3; }
};

struct EmbreeBuild {
    EmbreeScene scene{nullptr, rtcReleaseScene};
    double seconds = 0;
    long long bytes = 0;  ///< Net bytes the device allocated during the commit.
};

/// Embree's MEDIUM build of `mesh`; times rtcCommitScene only (the geometry setup just records
/// the shared buffers).
EmbreeBuild buildEmbree(const EmbreeDevice& device, const SharedMesh& mesh) {
    EmbreeBuild b;
    b.scene.reset(rtcNewScene(device.get()));
    rtcSetSceneBuildQuality(b.scene.get(), RTC_BUILD_QUALITY_MEDIUM);
    rtcSetSceneFlags(b.scene.get(), RTC_SCENE_FLAG_NONE);
    RTCGeometry g = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_MEDIUM);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                               mesh.vertices.data(), 0, 3 * sizeof(float), mesh.vertexCount());
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, mesh.indices.data(),
                               0, 3 * sizeof(uint32_t), mesh.triangleCount());
    rtcCommitGeometry(g);
    rtcAttachGeometry(b.scene.get(), g);
    rtcReleaseGeometry(g);
    long long before = device.bytes();
    auto t0 = Clock::now();
    rtcCommitScene(b.scene.get());
    b.seconds = secondsSince(t0);
    b.bytes = device.bytes() - before;
    return b;
}

RTCRay toEmbree(const glint::TraversalRay& r) {
    RTCRay e{};
    e.org_x = r.origin.x, e.org_y = r.origin.y, e.org_z = r.origin.z;
    e.dir_x = r.dir.x, e.dir_y = r.dir.y, e.dir_z = r.dir.z;
    e.tnear = r.tMin, e.tfar = r.tMax;
    e.time = 0;
    e.mask = ~0u, e.id = 0, e.flags = 0;
    return e;
}

RTCIntersectContext embreeContext(bool coherent) {
    RTCIntersectContext c;
    rtcInitIntersectContext(&c);
    c.flags =
        coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    return c;
}

/// Embree's closest hit: distance (infinity for none) and triangle. Embree numbers the triangles
/// of the shared index buffer as Glint numbers its primitives, so the ids are comparable.
struct EmbreeHit {
    float t = kInf;
    uint32_t prim = 0;
};

EmbreeHit embreeIntersect(RTCScene scene, RTCIntersectContext& ctx, const RTCRay& ray) {
    RTCRayHit rh;
    rh.ray = ray;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return {};
    return {rh.ray.tfar, rh.hit.primID};
}

bool embreeOccluded(RTCScene scene, RTCIntersectContext& ctx, const RTCRay& ray) {
    RTCRay r = ray;
    rtcOccluded1(scene, &ctx, &r);
    return r.tfar < 0;  // Embree sets tfar to -inf on a hit.
}

struct alignas(32) ValidMask8 {
    int lane[8];
};

/// Closest hits of an 8-ray packet (t = infinity for a miss or an invalid lane).
void embreeIntersect8(RTCScene scene, RTCIntersectContext& ctx, const ValidMask8& valid,
                      const RTCRay8& rays, EmbreeHit (&hits)[8]) {
    RTCRayHit8 rh;
    rh.ray = rays;
    for (int l = 0; l < 8; ++l) {
        rh.hit.geomID[l] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0][l] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect8(valid.lane, scene, &ctx, &rh);
    for (int l = 0; l < 8; ++l)
        hits[l] = valid.lane[l] && rh.hit.geomID[l] != RTC_INVALID_GEOMETRY_ID
                      ? EmbreeHit{rh.ray.tfar[l], rh.hit.primID[l]}
                      : EmbreeHit{};
}

// ---------------------------------------------------------------------------------------------
// Meshes

/// A triangle mesh as both libraries see it: Glint's primitives (world-space triangles) and the
/// same triangles in Embree's shared buffers. Triangles Glint drops (zero area) are left out of
/// both.
struct BenchMesh {
    std::string name;
    std::unique_ptr<glint::Scene> scene;          ///< For a loaded scene: owns the primitives.
    std::unique_ptr<glint::Primitives> ownPrims;  ///< For a generated mesh.
    const glint::Primitives* prims = nullptr;
    SharedMesh embree;
    size_t dropped = 0;

    uint32_t triangles() const { return prims->triangleCount(); }
};

/// The torus + ground of bench/torus.h; also returns the torus's bounding box (without the
/// ground), where the random rays start.
BenchMesh makeTorusMesh(bool quick, Vec3& boxLo, Vec3& boxHi) {
    glint::bench::Mesh mesh =
        quick ? glint::bench::rippledTorus(200, 100) : glint::bench::rippledTorus();
    boxLo = Vec3(glint::kInfinity), boxHi = Vec3(-glint::kInfinity);
    for (const auto& v : mesh.vertices) {
        boxLo = min(boxLo, Vec3(v[0], v[1], v[2]));
        boxHi = max(boxHi, Vec3(v[0], v[1], v[2]));
    }
    glint::bench::addGround(mesh);

    BenchMesh m;
    m.name = "torus + ground";
    m.ownPrims = std::make_unique<glint::Primitives>();
    m.prims = m.ownPrims.get();
    for (const auto& v : mesh.vertices)
        for (double c : v) m.embree.vertices.push_back(static_cast<float>(c));
    m.embree.vertices.push_back(0);  // Embree may read 16 bytes at the last vertex.
    m.embree.indices.reserve(3 * mesh.triangles.size());
    for (const auto& t : mesh.triangles) {
        auto vertex = [&](uint32_t i) {
            const auto& p = mesh.vertices[i];
            return Vec3(p[0], p[1], p[2]);
        };
        if (m.ownPrims->addTriangle(vertex(t[0]), vertex(t[1]), vertex(t[2]), nullptr, 0))
            m.embree.indices.insert(m.embree.indices.end(), t.begin(), t.end());
        else
            ++m.dropped;
    }
    return m;
}

/// The scene7 dragon, loaded by Glint's loader; Embree gets Glint's stored triangles as a soup.
BenchMesh makeSceneMesh(const std::string& path) {
    std::vector<glint::Diagnostic> warnings;
    BenchMesh m;
    m.name = "dragon (scene7)";
    m.scene = glint::loadCourseScene(path, warnings);
    m.prims = &m.scene->primitives;
    uint32_t n = m.prims->triangleCount();
    m.embree.vertices.reserve(9 * size_t{n} + 1);
    m.embree.indices.reserve(3 * size_t{n});
    for (uint32_t id = 0; id < n; ++id) {
        for (const glint::Vec3f& p : m.prims->triangleVertices(id)) {
            m.embree.indices.push_back(static_cast<uint32_t>(m.embree.vertices.size() / 3));
            m.embree.vertices.insert(m.embree.vertices.end(), {p.x, p.y, p.z});
        }
    }
    m.embree.vertices.push_back(0);
    if (m.prims->sphereCount() > 0)
        std::fprintf(stderr, "note: %s has %u spheres; Glint's BVH includes them, Embree's not\n",
                     path.c_str(), m.prims->sphereCount());
    return m;
}

// ---------------------------------------------------------------------------------------------
// Build

struct BuildFigures {
    double glintSeconds = 0, embreeSeconds = 0;
    size_t glintBytes = 0;
    long long embreeBytes = 0;
};

BuildFigures measureBuild(const BenchMesh& m, int threads, const Options& o) {
    EmbreeDevice device(threads, o.embreeIsa);
    glint::ThreadPool pool(threads);  // like the device, made once, outside the timings
    std::vector<double> glintTimes, embreeTimes;
    BuildFigures f;
    for (int run = -1; run < o.runs; ++run) {  // run -1 warms up both
        auto glintBuild = [&] {
            glint::Bvh bvh;
            auto t0 = Clock::now();
            bvh.build(*m.prims, {.pool = &pool});
            double s = secondsSince(t0);
            if (run >= 0) glintTimes.push_back(s);
            f.glintBytes = bvh.stats().bytes;
        };
        auto embreeBuild = [&] {
            EmbreeBuild b = buildEmbree(device, m.embree);
            if (run >= 0) embreeTimes.push_back(b.seconds);
            f.embreeBytes = b.bytes;
        };
        if (run % 2 == 0) {
            glintBuild();
            embreeBuild();
        } else {
            embreeBuild();
            glintBuild();
        }
    }
    f.glintSeconds = median(glintTimes);
    f.embreeSeconds = median(embreeTimes);
    return f;
}

// ---------------------------------------------------------------------------------------------
// Rays

/// Pinhole camera rays through pixel centres, row by row from the top left.
std::vector<glint::Ray> cameraRays(const glint::bench::View& view) {
    Vec3 eye(view.eye[0], view.eye[1], view.eye[2]), at(view.at[0], view.at[1], view.at[2]),
        up(view.up[0], view.up[1], view.up[2]);
    Vec3 w = normalize(eye - at), u = normalize(cross(up, w)), v = cross(w, u);
    double tanX = std::tan(view.fovxDegrees * std::numbers::pi / 360);
    double tanY = tanX * view.height / view.width;
    double halfW = view.width / 2.0, halfH = view.height / 2.0;
    std::vector<glint::Ray> rays;
    rays.reserve(static_cast<size_t>(view.width) * view.height);
    for (int y = 0; y < view.height; ++y)
        for (int x = 0; x < view.width; ++x) {
            double a = tanX * (x + 0.5 - halfW) / halfW, b = tanY * (halfH - (y + 0.5)) / halfH;
            rays.push_back(glint::Ray{eye, normalize(u * a + v * b - w), 0, glint::kInfinity});
        }
    return rays;
}

/// Origins uniform in [lo, hi], directions uniform on the unit sphere, fixed seed.
std::vector<glint::Ray> randomRays(size_t count, const Vec3& lo, const Vec3& hi) {
    std::mt19937_64 rng(0x5eed'6c1e'4e75ULL);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<glint::Ray> rays;
    rays.reserve(count);
    for (size_t i = 0; i < count; ++i) {
        Vec3 o(lo.x + (hi.x - lo.x) * unit(rng), lo.y + (hi.y - lo.y) * unit(rng),
               lo.z + (hi.z - lo.z) * unit(rng));
        double z = 2 * unit(rng) - 1, phi = 2 * std::numbers::pi * unit(rng);
        double s = std::sqrt(std::max(0.0, 1 - z * z));
        rays.push_back(
            glint::Ray{o, Vec3(s * std::cos(phi), s * std::sin(phi), z), 0, glint::kInfinity});
    }
    return rays;
}

/// One ray set in both libraries' formats, the same float values in each.
struct RaySet {
    std::vector<glint::TraversalRay> glint;
    std::vector<RTCRay> embree;

    explicit RaySet(const std::vector<glint::Ray>& rays) {
        glint.reserve(rays.size());
        embree.reserve(rays.size());
        for (const glint::Ray& r : rays) {
            glint.emplace_back(r);
            embree.push_back(toEmbree(glint.back()));
        }
    }
    size_t size() const { return glint.size(); }
};

/// Camera rays in 8-ray packets of 4x2 pixels, in both formats.
struct PacketSet {
    std::vector<glint::RayPacket8> glint;
    std::vector<RTCRay8> embree;
    std::vector<ValidMask8> valid;
    size_t rays = 0;

    PacketSet(const RaySet& camera, int width, int height) {
        for (int by = 0; by < height; by += 2)
            for (int bx = 0; bx < width; bx += 4) {
                glint::RayPacket8 g{};
                RTCRay8 e{};
                ValidMask8 v{};
                g.active = 0;
                for (int l = 0; l < 8; ++l) {
                    int x = bx + l % 4, y = by + l / 4;
                    bool inside = x < width && y < height;
                    // Lanes outside the image repeat the block's first ray, marked inactive.
                    size_t i = inside ? static_cast<size_t>(y) * width + x
                                      : static_cast<size_t>(by) * width + bx;
                    const glint::TraversalRay& r = camera.glint[i];
                    g.set(l, r);
                    if (inside) g.active = static_cast<uint8_t>(g.active | (1u << l));
                    e.org_x[l] = r.origin.x, e.org_y[l] = r.origin.y, e.org_z[l] = r.origin.z;
                    e.dir_x[l] = r.dir.x, e.dir_y[l] = r.dir.y, e.dir_z[l] = r.dir.z;
                    e.tnear[l] = r.tMin, e.tfar[l] = r.tMax, e.time[l] = 0;
                    e.mask[l] = ~0u, e.id[l] = static_cast<unsigned>(l), e.flags[l] = 0;
                    v.lane[l] = inside ? -1 : 0;
                    rays += inside;
                }
                glint.push_back(g);
                embree.push_back(e);
                valid.push_back(v);
            }
    }
    size_t size() const { return glint.size(); }
};

// ---------------------------------------------------------------------------------------------
// Traversal

struct Traversal {
    const glint::Primitives& prims;
    const glint::Bvh& bvh;
    RTCScene scene;
};

enum class Kind { Intersect, Occluded, Packet8 };

struct Workload {
    const char* name;
    const char* api;
    double goal;  ///< Glint/Embree ratio the issue asks for.
    Kind kind;
    bool coherent;
    const RaySet* rays = nullptr;
    const PacketSet* packets = nullptr;

    size_t items() const { return kind == Kind::Packet8 ? packets->size() : rays->size(); }
    size_t rayCount() const { return kind == Kind::Packet8 ? packets->rays : rays->size(); }
    size_t chunk() const { return kind == Kind::Packet8 ? 512 : 4096; }
};

/// Glint's per-ray set-up (reciprocal direction, shear frame) happens inside the timed loop,
/// from the same float ray Embree reads, as Embree does its own inside each call.
glint::TraversalRay glintRay(const RTCRay& e) {
    return {{e.org_x, e.org_y, e.org_z}, {e.dir_x, e.dir_y, e.dir_z}, e.tnear, e.tfar};
}

/// Glint over items [begin, end) of a workload; returns the number of hits.
uint64_t runGlint(const Traversal& tr, const Workload& w, size_t begin, size_t end) {
    uint64_t hits = 0;
    switch (w.kind) {
        case Kind::Intersect:
            for (size_t i = begin; i < end; ++i) {
                glint::Hit h;
                hits += tr.bvh.intersect(glintRay(w.rays->embree[i]), h);
            }
            break;
        case Kind::Occluded:
            for (size_t i = begin; i < end; ++i)
                hits += tr.bvh.occluded(glintRay(w.rays->embree[i]));
            break;
        case Kind::Packet8:
            for (size_t i = begin; i < end; ++i) {
                // Set up from the same float data Embree's packet holds, inside the timed loop.
                const RTCRay8& e = w.packets->embree[i];
                glint::RayPacket8 p;
                p.active = w.packets->glint[i].active;
                for (int l = 0; l < 8; ++l)
                    p.set(l, {{e.org_x[l], e.org_y[l], e.org_z[l]},
                              {e.dir_x[l], e.dir_y[l], e.dir_z[l]},
                              e.tnear[l],
                              e.tfar[l]});
                glint::HitPacket8 h;
                tr.bvh.intersect8(p, h);
                for (int l = 0; l < 8; ++l) hits += ((p.active >> l) & 1u) && h.t[l] < kInf;
            }
            break;
    }
    return hits;
}

/// Embree over items [begin, end) of a workload; returns the number of hits.
uint64_t runEmbree(const Traversal& tr, const Workload& w, size_t begin, size_t end) {
    RTCIntersectContext ctx = embreeContext(w.coherent);
    uint64_t hits = 0;
    switch (w.kind) {
        case Kind::Intersect:
            for (size_t i = begin; i < end; ++i)
                hits += embreeIntersect(tr.scene, ctx, w.rays->embree[i]).t < kInf;
            break;
        case Kind::Occluded:
            for (size_t i = begin; i < end; ++i)
                hits += embreeOccluded(tr.scene, ctx, w.rays->embree[i]);
            break;
        case Kind::Packet8:
            for (size_t i = begin; i < end; ++i) {
                EmbreeHit h[8];
                embreeIntersect8(tr.scene, ctx, w.packets->valid[i], w.packets->embree[i], h);
                for (int l = 0; l < 8; ++l) hits += h[l].t < kInf;
            }
            break;
    }
    return hits;
}

struct TraversalFigures {
    double glintMrays = 0, embreeMrays = 0;
    uint64_t glintHits = 0, embreeHits = 0;
};

/// Each timed sample repeats the whole ray set until it lasts at least this long, so that small
/// sets (--quick) are not timed at the scale of the scheduler's noise.
constexpr double kMinSampleSeconds = 0.2;

TraversalFigures measureTraversal(const Traversal& tr, const Workload& w, int threads, int runs) {
    std::vector<double> glintRates, embreeRates;
    TraversalFigures f;
    int glintRepeats = 1, embreeRepeats = 1;
    // One pass of the ray set, repeated `repeats` times; returns rays per second.
    auto timed = [&](auto run, uint64_t& hits, int repeats) {
        auto t0 = Clock::now();
        for (int i = 0; i < repeats; ++i)
            hits = parallelChunks(threads, w.items(), w.chunk(),
                                  [&](size_t b, size_t e) { return run(tr, w, b, e); });
        return static_cast<double>(w.rayCount()) * repeats / secondsSince(t0);
    };
    auto repeatsFor = [&](double raysPerSecond) {
        double seconds = static_cast<double>(w.rayCount()) / raysPerSecond;
        return static_cast<int>(std::clamp(std::ceil(kMinSampleSeconds / seconds), 1.0, 1000.0));
    };
    // Warm-up pass of each, which also sets how often a sample repeats the set.
    glintRepeats = repeatsFor(timed(runGlint, f.glintHits, 1));
    embreeRepeats = repeatsFor(timed(runEmbree, f.embreeHits, 1));
    for (int run = 0; run < runs; ++run) {
        auto glintSample = [&] {
            glintRates.push_back(timed(runGlint, f.glintHits, glintRepeats));
        };
        auto embreeSample = [&] {
            embreeRates.push_back(timed(runEmbree, f.embreeHits, embreeRepeats));
        };
        if (run % 2 == 0) {
            glintSample();
            embreeSample();
        } else {
            embreeSample();
            glintSample();
        }
    }
    f.glintMrays = median(glintRates) / 1e6;
    f.embreeMrays = median(embreeRates) / 1e6;
    return f;
}

/// Largest vertex coordinate magnitude of primitive `id` if it is a triangle, else 0.
float triangleScale(const glint::Primitives& prims, uint32_t id) {
    if (id >= prims.triangleCount()) return 0;
    float m = 0;
    for (const glint::Vec3f& p : prims.triangleVertices(id))
        m = std::max({m, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    return m;
}

enum class Match { Same, WithinPrecision, Differ };

/// Same if both miss, or both hit with t within 1e-4 relative. WithinPrecision if both hit and t
/// differs by more but by at most 8 float ulps of the largest coordinate of the triangles hit:
/// the float test's own error on big triangles (the 200 x 200 ground) near the ray origin.
Match compareHits(const glint::Primitives& prims, float tg, uint32_t primG, const EmbreeHit& e) {
    if (tg == kInf || e.t == kInf) return tg == e.t ? Match::Same : Match::Differ;
    float diff = std::abs(tg - e.t);
    if (diff <= 1e-4f * std::max(tg, e.t)) return Match::Same;
    float scale = std::max(triangleScale(prims, primG), triangleScale(prims, e.prim));
    return diff <= 8 * scale * std::numeric_limits<float>::epsilon() ? Match::WithinPrecision
                                                                     : Match::Differ;
}

struct Agreement {
    uint64_t rays = 0, precisionOnly = 0, differ = 0;
    double percent(uint64_t bad) const {
        return rays ? 100.0 * static_cast<double>(rays - bad) / static_cast<double>(rays) : 100;
    }
};

/// Per-ray results of both libraries for a workload, compared (untimed, all threads).
Agreement compare(const Traversal& tr, const Workload& w) {
    int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    std::atomic<uint64_t> precisionOnly{0}, differ{0};
    uint64_t rays = parallelChunks(threads, w.items(), w.chunk(), [&](size_t begin, size_t end) {
        RTCIntersectContext ctx = embreeContext(w.coherent);
        uint64_t count = 0, loose = 0, bad = 0;
        auto tally = [&](Match m) {
            ++count;
            loose += m == Match::WithinPrecision;
            bad += m == Match::Differ;
        };
        for (size_t i = begin; i < end; ++i) {
            switch (w.kind) {
                case Kind::Intersect: {
                    glint::Hit h;
                    float tg = tr.bvh.intersect(w.rays->glint[i], h) ? h.t : kInf;
                    EmbreeHit e = embreeIntersect(tr.scene, ctx, w.rays->embree[i]);
                    tally(compareHits(tr.prims, tg, h.primId, e));
                    break;
                }
                case Kind::Occluded:
                    tally(tr.bvh.occluded(w.rays->glint[i]) ==
                                  embreeOccluded(tr.scene, ctx, w.rays->embree[i])
                              ? Match::Same
                              : Match::Differ);
                    break;
                case Kind::Packet8: {
                    const glint::RayPacket8& p = w.packets->glint[i];
                    glint::HitPacket8 h;
                    tr.bvh.intersect8(p, h);
                    EmbreeHit e[8];
                    embreeIntersect8(tr.scene, ctx, w.packets->valid[i], w.packets->embree[i], e);
                    for (int l = 0; l < 8; ++l)
                        if ((p.active >> l) & 1u)
                            tally(compareHits(tr.prims, h.t[l], h.primId[l], e[l]));
                    break;
                }
            }
        }
        precisionOnly.fetch_add(loose, std::memory_order_relaxed);
        differ.fetch_add(bad, std::memory_order_relaxed);
        return count;
    });
    return {rays, precisionOnly.load(), differ.load()};
}

/// Shadow rays from each point where Embree's camera ray hits towards the light: origin moved
/// 1e-4 along the shadow ray, tMax the distance from there to the light.
std::vector<glint::Ray> shadowRays(const std::vector<glint::Ray>& camera, const RaySet& cameraSet,
                                   RTCScene scene, const Vec3& light) {
    std::vector<glint::Ray> rays;
    RTCIntersectContext ctx = embreeContext(true);
    for (size_t i = 0; i < camera.size(); ++i) {
        float t = embreeIntersect(scene, ctx, cameraSet.embree[i]).t;
        if (t == kInf) continue;
        Vec3 p = camera[i].at(t);
        Vec3 d = normalize(light - p);
        Vec3 o = p + d * 1e-4;
        rays.push_back(glint::Ray{o, d, 0, length(light - o)});
    }
    return rays;
}

// ---------------------------------------------------------------------------------------------
// Output

void printHeader(const Options& o) {
    unsigned hw = std::thread::hardware_concurrency();
    __builtin_cpu_init();
    bool avx2 = __builtin_cpu_supports("avx2"), avx512 = __builtin_cpu_supports("avx512f");
    std::printf(
        "Glint vs Intel Embree %s: BVH build and traversal (issue 3), peers measured in "
        "the same run\n",
        RTC_VERSION_STRING);
    std::printf("Machine:  %s, %u hardware threads, AVX2 %s, AVX-512 %s\n", cpuName().c_str(), hw,
                avx2 ? "yes" : "no", avx512 ? "yes" : "no");
    std::printf("Glint:    Bvh::isa() = %s\n", glint::Bvh::isa());
    double load = loadAverage();
    if (load >= 0)
        std::printf("Load:     1-minute load average %.2f at start%s\n", load,
                    load > 0.5 ? " (other processes are running: figures are noisy)" : "");
    std::printf("Embree:   ISA %s, MEDIUM build quality, single-ray and 8-wide packet API\n",
                o.embreeIsa.empty() ? "its widest for this CPU (--embree-isa caps it)"
                                    : ("at most " + o.embreeIsa).c_str());
    std::printf("Method:   medians of %d runs, Glint and Embree alternating within each run%s\n\n",
                o.runs, o.quick ? "; --quick (small mesh and image: not the issue's figures)" : "");
}

const char* mark(double ratio, double goal) { return ratio >= goal ? "met" : "below"; }

void printBuildTable(const std::vector<const BenchMesh*>& meshes,
                     const std::vector<std::array<BuildFigures, 2>>& figures) {
    std::printf(
        "BVH build, Mtris/s (seconds)  thr    Glint               Embree MEDIUM"
        "        Glint/Embree  goal\n");
    for (size_t m = 0; m < meshes.size(); ++m) {
        double tris = meshes[m]->triangles();
        for (size_t t = 0; t < kThreadCounts.size(); ++t) {
            const BuildFigures& f = figures[m][t];
            double g = tris / f.glintSeconds / 1e6, e = tris / f.embreeSeconds / 1e6;
            std::string label =
                t == 0 ? meshes[m]->name : "  " + withCommas(meshes[m]->triangles()) + " tris";
            std::printf("%-29s %3d  %7.2f (%6.3f s)  %7.2f (%6.3f s)  %8.2fx", label.c_str(),
                        kThreadCounts[t], g, f.glintSeconds, e, f.embreeSeconds, g / e);
            if (t == 0) {
                std::printf("     >=1.0x %s\n", mark(g / e, 1.0));
            } else {
                const BuildFigures& one = figures[m][0];
                std::printf("     scaling: Glint %.2fx, Embree %.2fx\n",
                            one.glintSeconds / f.glintSeconds, one.embreeSeconds / f.embreeSeconds);
            }
        }
    }
    std::printf(
        "\nMemory, bytes per triangle    Glint 1T  Glint 2T  Embree 1T  Embree 2T  "
        "goal (Glint)\n");
    for (size_t m = 0; m < meshes.size(); ++m) {
        double tris = meshes[m]->triangles();
        const auto& f = figures[m];
        double g1 = static_cast<double>(f[0].glintBytes) / tris,
               g2 = static_cast<double>(f[1].glintBytes) / tris;
        std::printf("%-29s %8.1f  %8.1f  %9.1f  %9.1f  <=64 %s\n", meshes[m]->name.c_str(), g1, g2,
                    static_cast<double>(f[0].embreeBytes) / tris,
                    static_cast<double>(f[1].embreeBytes) / tris,
                    std::max(g1, g2) <= 64 ? "met" : "over");
    }
    std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
    Options o = parseOptions(argc, argv);
    try {
        printHeader(o);

        // ---- Meshes and builds
        progress("generating the torus");
        Vec3 boxLo, boxHi;
        BenchMesh torus = makeTorusMesh(o.quick, boxLo, boxHi);
        std::vector<std::array<BuildFigures, 2>> buildFigures;
        std::vector<const BenchMesh*> meshes{&torus};
        for (size_t t = 0; t < kThreadCounts.size(); ++t) {
            if (t == 0) buildFigures.emplace_back();
            progress("building the torus, " + std::to_string(kThreadCounts[t]) + " thread(s)");
            buildFigures[0][t] = measureBuild(torus, kThreadCounts[t], o);
        }
        std::unique_ptr<BenchMesh> dragon;
        if (std::filesystem::exists(o.scene7)) {
            progress("loading " + o.scene7);
            dragon = std::make_unique<BenchMesh>(makeSceneMesh(o.scene7));
            meshes.push_back(dragon.get());
            buildFigures.emplace_back();
            for (size_t t = 0; t < kThreadCounts.size(); ++t) {
                progress("building the dragon, " + std::to_string(kThreadCounts[t]) + " thread(s)");
                buildFigures[1][t] = measureBuild(*dragon, kThreadCounts[t], o);
            }
        } else {
            std::fprintf(stderr, "note: %s not found; skipping the dragon\n", o.scene7.c_str());
        }
        printBuildTable(meshes, buildFigures);
        std::fflush(stdout);
        if (o.buildOnly) return 0;
        dragon.reset();

        // ---- Traversal on the torus
        progress("building the traversal BVHs and rays");
        glint::Bvh bvh;
        bvh.build(*torus.prims, glint::BvhBuildOptions{0});
        EmbreeDevice device(0, o.embreeIsa);
        EmbreeBuild embree = buildEmbree(device, torus.embree);
        Traversal tr{*torus.prims, bvh, embree.scene.get()};

        glint::bench::View view;
        if (o.quick) view.width = 320, view.height = 180;
        std::vector<glint::Ray> camera = cameraRays(view);
        RaySet primary(camera);
        Vec3 light(view.light[0], view.light[1], view.light[2]);
        RaySet shadow(shadowRays(camera, primary, tr.scene, light));
        camera = {};
        RaySet random(randomRays(o.quick ? 200'000 : 2'000'000, boxLo, boxHi));
        PacketSet packets(primary, view.width, view.height);

        std::vector<Workload> workloads{
            {"primary", "intersect / rtcIntersect1", 1.0, Kind::Intersect, true, &primary},
            {"shadow", "occluded / rtcOccluded1", 1.0, Kind::Occluded, true, &shadow},
            {"random", "intersect / rtcIntersect1", 0.8, Kind::Intersect, false, &random},
            {"random", "occluded / rtcOccluded1", 0.8, Kind::Occluded, false, &random},
            {"packets 4x2", "intersect8 / rtcIntersect8", 0.9, Kind::Packet8, true, nullptr,
             &packets},
        };

        std::printf("Traversal, %s (%s tris), %dx%d camera, Mrays/s\n", torus.name.c_str(),
                    withCommas(torus.triangles()).c_str(), view.width, view.height);
        std::printf("%-12s %-27s %10s %4s %8s %8s %13s  %s\n", "rays", "Glint / Embree call",
                    "count", "thr", "Glint", "Embree", "Glint/Embree", "goal");
        std::vector<Agreement> agreements;
        for (const Workload& w : workloads) {
            for (size_t t = 0; t < kThreadCounts.size(); ++t) {
                progress(std::string(w.name) + " " + w.api + ", " +
                         std::to_string(kThreadCounts[t]) + " thread(s)");
                TraversalFigures f = measureTraversal(tr, w, kThreadCounts[t], o.runs);
                double ratio = f.glintMrays / f.embreeMrays;
                if (t == 0)
                    std::printf("%-12s %-27s %10s", w.name, w.api,
                                withCommas(w.rayCount()).c_str());
                else
                    std::printf("%-12s %-27s %10s", "", "", "");
                std::printf(" %4d %8.2f %8.2f %12.2fx  >=%.1fx %s\n", kThreadCounts[t],
                            f.glintMrays, f.embreeMrays, ratio, w.goal, mark(ratio, w.goal));
                std::fflush(stdout);
            }
            progress(std::string("comparing results: ") + w.name + " " + w.api);
            agreements.push_back(compare(tr, w));
        }

        std::printf(
            "\nAgreement, Glint vs Embree on the same rays: same hit/miss and, where both hit, t "
            "within 1e-4\nrelative; then also counting t within 8 float ulps of the hit "
            "triangle's largest coordinate\n(float precision of big triangles near the origin); "
            "expect > 99.9%%\n");
        std::printf("%-12s %-27s %10s %10s %14s %10s\n", "rays", "Glint / Embree call", "count",
                    "1e-4 rel", "+ float prec.", "differ");
        for (size_t i = 0; i < workloads.size(); ++i) {
            const Agreement& a = agreements[i];
            double strict = a.percent(a.differ + a.precisionOnly), loose = a.percent(a.differ);
            std::printf("%-12s %-27s %10s %9.4f%% %13.4f%% %10s %s\n", workloads[i].name,
                        workloads[i].api, withCommas(a.rays).c_str(), strict, loose,
                        withCommas(a.differ).c_str(), loose > 99.9 ? "ok" : "LOW");
        }

        std::printf(
            "\nNotes: Glint and Embree were measured in this run, on this machine, on identical "
            "float rays\n"
            "(Glint's per-ray set-up timed, as Embree's is) and the same float triangles (%zu "
            "zero-area ones Glint drops left out of both).\n"
            "Build time: wall clock of Bvh::build and of rtcCommitScene (Embree device made with "
            "threads=N).\n"
            "Memory: Glint Bvh::stats().bytes; Embree the net bytes its memory monitor reported "
            "during\n"
            "rtcCommitScene (vertex and index buffers are shared application buffers, not "
            "counted).\n"
            "Glint's figure is what its BVH reports as everything traversal reads (nodes and leaf "
            "data).\n"
            "Traversal: std::thread workers pull chunks of 4096 rays (512 packets) from an atomic "
            "counter;\n"
            "Embree traverses on the calling threads. Shadow rays start at Embree's primary "
            "hits.\nEach traversal sample repeats its ray set to last at least %.1f s; the rate "
            "is rays/s over it.\n",
            torus.dropped, kMinSampleSeconds);
        double load = loadAverage();
        if (load >= 0) std::printf("1-minute load average at the end: %.2f\n", load);
        embree.scene.reset();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "glint_traversal_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
