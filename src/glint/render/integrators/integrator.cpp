#include "glint/render/integrators/integrator.h"

#include <cmath>

#include "glint/core/error.h"
#include "glint/render/integrators/path.h"
#include "glint/render/integrators/whitted.h"

namespace glint {

Vec3 repairRadiance(const Vec3& c, RayCounts& counts) {
    if (!isFinite(c)) ++counts.nonFinite;
    return finiteRadiance(c);
}

const std::vector<IntegratorInfo>& integrators() {
    // A new integrator is a class implementing Integrator and one row here.
    static const std::vector<IntegratorInfo> table = {
        {"whitted",
         "the course's recursive ray tracer (OpenGL-style lights, shadows, mirrors) and its "
         "extensions",
         [](const Scene& scene, const IntegratorOptions& options) -> std::unique_ptr<Integrator> {
             return std::make_unique<WhittedIntegrator>(scene, options.spp);
         }},
        {"path",
         "a physically based path tracer: global illumination, multiple importance sampling, "
         "emissive surfaces and the environment as lights",
         [](const Scene& scene, const IntegratorOptions&) -> std::unique_ptr<Integrator> {
             return std::make_unique<PathIntegrator>(scene);
         }},
    };
    return table;
}

const IntegratorInfo* findIntegrator(std::string_view name) {
    for (const IntegratorInfo& info : integrators())
        if (info.name == name) return &info;
    return nullptr;
}

std::string integratorNameList() {
    std::string list;
    for (const IntegratorInfo& info : integrators()) {
        if (!list.empty()) list += ", ";
        list += info.name;
    }
    return list;
}

std::unique_ptr<Integrator> makeIntegrator(const Scene& scene, const IntegratorOptions& options) {
    const IntegratorInfo* info = findIntegrator(scene.integrator);
    if (!info)
        throw RenderError("unknown integrator '" + scene.integrator + "' (Glint has " +
                          integratorNameList() + ")");
    return info->make(scene, options);
}

}  // namespace glint
