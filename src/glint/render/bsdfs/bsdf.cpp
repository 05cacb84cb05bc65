#include "glint/render/bsdfs/bsdf.h"

#include <ostream>

namespace glint {

Bsdf bsdfFromMaterial(const Material& m) {
    auto unit = [](const Vec3& c) { return min(max(c, Vec3(0)), Vec3(1)); };
    if (m.transmissive()) return {Dielectric{m.ior, unit(m.transmission), m.roughness}};
    Vec3 d = unit(m.diffuse), s = unit(m.specular);
    if (s == Vec3(0)) return {Lambertian{d}};
    for (int c = 0; c < 3; ++c) {
        double sum = d[c] + s[c];
        if (sum > 1) {
            d[c] /= sum;
            s[c] /= sum;
        }
    }
    return {DiffuseSpecular{d, s, m.roughness}};
}

std::ostream& operator<<(std::ostream& out, BsdfFlags flags) {
    static constexpr const char* kNames[] = {"Reflection", "Transmission", "Diffuse", "Glossy",
                                             "Specular"};
    const char* separator = "";
    for (int bit = 0; bit < 5; ++bit)
        if (hasAny(flags, static_cast<BsdfFlags>(1 << bit))) {
            out << separator << kNames[bit];
            separator = " | ";
        }
    if (*separator == '\0') out << "None";
    return out;
}

std::ostream& operator<<(std::ostream& out, const BsdfSample& s) {
    return out << "BsdfSample{wi " << s.wi << ", f " << s.f << ", pdf " << s.pdf << ", " << s.flags
               << "}";
}

std::ostream& operator<<(std::ostream& out, const Bsdf& bsdf) {
    std::visit([&](const auto& lobe) { out << lobe; }, bsdf.lobe_);
    return out;
}

}  // namespace glint
