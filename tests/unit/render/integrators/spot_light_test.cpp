// A spot light through the integrators, which know it only as a Light (render/lights/): a
// white floor lit from above is lit as a point light of the same intensity lights it within
// the inner cone, not at all beyond the outer cone, and by a fading ring between, in the Whitted
// integrator and the path tracer alike.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "glint/render/renderer.h"
#include "unit/test_support.h"

namespace glint {
namespace {

constexpr int kSize = 41;  // odd: the centre pixel looks straight down the spot's axis

/// A white diffuse floor seen from above, lit by `light` alone.
std::unique_ptr<Scene> floorUnder(const LightSpec& light, const std::string& integrator) {
    auto made = std::make_unique<Scene>();
    Scene& scene = *made;
    scene.width = scene.height = kSize;
    scene.integrator = integrator;
    scene.maxDepth = 2;
    scene.camera = CameraSpec{{0, 4, 0}, {0, 0, 0}, {0, 0, -1}, 90};
    Material white = test::makeMaterial({0, 0, 0}, {0.8, 0.8, 0.8});
    const uint32_t m = scene.addMaterial(white);
    scene.primitives.addTriangle({-9, 0, -9}, {-9, 0, 9}, {9, 0, 9}, nullptr, m);
    scene.primitives.addTriangle({-9, 0, -9}, {9, 0, 9}, {9, 0, -9}, nullptr, m);
    scene.lights.push_back(light);
    scene.prepare();
    return made;
}

LightSpec spot() {
    LightSpec s;
    s.kind = LightSpec::Kind::Spot;
    s.position = {0, 2, 0};
    s.axis = {0, -1, 0};
    s.color = {6, 6, 6};
    s.attenuation = {0, 0, 1};
    s.cosInner = std::cos(0.25);
    s.cosOuter = std::cos(0.5);
    return s;
}

/// The floor's radiance at the pixel `r` pixels right of the centre.
double along(const Film& film, int r) { return film.at(kSize / 2 + r, kSize / 2).y; }

TEST(SpotLightRender, LightsTheFloorWithinItsConeOnlyInEveryIntegrator) {
    for (const std::string integrator : {"whitted", "path"}) {
        SCOPED_TRACE(integrator);
        RenderOptions options;
        options.threads = 1;
        options.spp = 4;
        const RenderResult result = render(*floorUnder(spot(), integrator), options);
        LightSpec point = spot();
        point.kind = LightSpec::Kind::Point;
        const RenderResult asPoint = render(*floorUnder(point, integrator), options);
        // The camera 4 above sees 8 across its 90 degrees: a pixel is 8 / 41 = 0.2 wide; the
        // cones' edges on the floor 2 below the light are 2 tan(0.25) = 0.51 and 2 tan(0.5) =
        // 1.09 from the centre. Pixels whose samples may fall on either side are not judged.
        const double pixel = 8.0 / kSize;
        for (int r = 0; r <= kSize / 2; ++r) {
            const double x = r * pixel, angle = std::atan(x / 2);
            if (angle < 0.19) {  // wholly within the inner cone: as the point light
                EXPECT_NEAR(along(result.film, r), along(asPoint.film, r),
                            1e-9 * along(asPoint.film, r))
                    << r;
                EXPECT_GT(along(result.film, r), 0.1) << r;
            } else if (angle >
                       0.56) {  // wholly beyond the outer cone: dark (nothing else lights it)
                EXPECT_EQ(along(result.film, r), 0) << r;
                EXPECT_GT(along(asPoint.film, r), 0) << r;
            } else if (angle > 0.28 && angle < 0.47) {  // the ring: dimmer than the point light
                EXPECT_GT(along(result.film, r), 0) << r;
                EXPECT_LT(along(result.film, r), along(asPoint.film, r)) << r;
            }
        }
    }
}

}  // namespace
}  // namespace glint
