// Scene-file commands for the layers of glTF's material extensions (docs/scene-format.md,
// "Layers"): clearcoat, sheen, specularfactor, anisotropy, iridescence, diffusetransmission.
// Each makes the current material physically based, as `metallic` does.

#include <numbers>

#include "glint/io/course/course_parser.h"

namespace glint::course {

double Parser::unitArgument(int i, const char* what) const {
    const double x = real(i);
    if (!(x >= 0 && x <= 1))
        fail(i, std::string(what) + " must be between 0 and 1, got " + quoted(i));
    return x;
}

Vec3 Parser::unitColour(int i, const char* what) const {
    return {unitArgument(i, what), unitArgument(i + 1, what), unitArgument(i + 2, what)};
}

void Parser::cmdClearcoat() {
    PbrMaterial& p = builder_.editPbr();
    p.clearcoat = unitArgument(1, "clearcoat");
    p.clearcoatRoughness = ntok_ > 2 ? unitArgument(2, "clearcoat roughness") : 0;
}

void Parser::cmdSheen() {
    PbrMaterial& p = builder_.editPbr();
    p.sheenColor = unitColour(1, "sheen colour");
    p.sheenRoughness = ntok_ > 4 ? unitArgument(4, "sheen roughness") : 0.5;
}

void Parser::cmdSpecularFactor() {
    if (ntok_ == 3 || ntok_ == 4)
        fail(ntok_ - 1, "specularfactor takes a factor and, optionally, three colour numbers");
    PbrMaterial& p = builder_.editPbr();
    p.specular = unitArgument(1, "specular factor");
    if (ntok_ > 2) {
        p.specularColor = vec3(2);
        for (int k = 2; k < 5; ++k)
            if (!(real(k) >= 0)) fail(k, "specular colour must not be negative, got " + quoted(k));
    } else {
        p.specularColor = Vec3(1);
    }
}

void Parser::cmdAnisotropy() {
    PbrMaterial& p = builder_.editPbr();
    p.anisotropy = unitArgument(1, "anisotropy");
    p.anisotropyRotation = ntok_ > 2 ? real(2) * std::numbers::pi / 180 : 0;
}

void Parser::cmdIridescence() {
    PbrMaterial& p = builder_.editPbr();
    p.iridescence = unitArgument(1, "iridescence");
    p.iridescenceIor = 1.3;
    p.iridescenceThicknessMax = 400;
    if (ntok_ > 2) {
        p.iridescenceIor = real(2);
        if (!(p.iridescenceIor >= 1 && p.iridescenceIor <= 4))
            fail(2, "the film's index must be between 1 and 4, got " + quoted(2));
    }
    if (ntok_ > 3) {
        p.iridescenceThicknessMax = real(3);
        if (!(p.iridescenceThicknessMax >= 0 && p.iridescenceThicknessMax <= 10000))
            fail(3, "the film's thickness must be between 0 and 10000 nm, got " + quoted(3));
    }
}

void Parser::cmdDiffuseTransmission() {
    if (ntok_ == 3 || ntok_ == 4)
        fail(ntok_ - 1, "diffusetransmission takes a factor and, optionally, three colour numbers");
    PbrMaterial& p = builder_.editPbr();
    p.diffuseTransmission = unitArgument(1, "diffuse transmission");
    p.diffuseTransmissionColor = ntok_ > 2 ? unitColour(2, "diffuse transmission colour") : Vec3(1);
}

}  // namespace glint::course
