#include "glint/render/bsdfs/diffuse_specular.h"

#include <ostream>

#include "glint/render/bsdfs/conductor.h"
#include "glint/render/bsdfs/lambertian.h"

namespace glint {

double DiffuseSpecular::specularProbability() const {
    double s = specular.x + specular.y + specular.z;
    double d = diffuse.x + diffuse.y + diffuse.z;
    return s > 0 ? s / (s + d) : 0;
}

Vec3 DiffuseSpecular::eval(const Vec3& wo, const Vec3& wi, TransportMode) const {
    Vec3 f = Lambertian{diffuse}.eval(wo, wi);
    if (alpha > 0) f += specular * Conductor{Vec3(1), alpha}.eval(wo, wi);
    return f;
}

double DiffuseSpecular::pdf(const Vec3& wo, const Vec3& wi, TransportMode) const {
    double ps = specularProbability();
    double pdf = (1 - ps) * Lambertian{diffuse}.pdf(wo, wi);
    if (alpha > 0) pdf += ps * Conductor{Vec3(1), alpha}.pdf(wo, wi);
    return pdf;
}

std::optional<BsdfSample> DiffuseSpecular::sample(const Vec3& wo, double uc, Point2 u,
                                                  TransportMode) const {
    double ps = specularProbability();
    // uc < ps chooses the specular lobe; uc / ps is then uniform again, for its own choice.
    std::optional<BsdfSample> s = uc < ps ? Conductor{Vec3(1), alpha}.sample(wo, uc / ps, u)
                                          : Lambertian{diffuse}.sample(wo, uc, u);
    if (!s) return std::nullopt;
    if (s->isSpecular()) {  // the mirror: a delta, chosen with probability ps
        s->f = s->f * specular;
        s->pdf *= ps;
        return s;
    }
    // Either lobe could have drawn wi: the mixture's value and density (one-sample MIS).
    s->f = eval(wo, s->wi);
    s->pdf = pdf(wo, s->wi);
    return s;
}

std::ostream& operator<<(std::ostream& out, const DiffuseSpecular& d) {
    out << "DiffuseSpecular{diffuse " << d.diffuse << ", specular " << d.specular << ", alpha "
        << d.alpha << "}";
    return out;
}

}  // namespace glint
