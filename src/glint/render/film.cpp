#include "glint/render/film.h"

namespace glint {

Image8 toImage8(const Film& film) {
    Image8 img{film.width(), film.height(), 3, {}};
    img.data.resize(static_cast<size_t>(img.width) * img.height * 3);
    size_t i = 0;
    for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x) {
            const Vec3& c = film.at(x, y);
            img.data[i++] = toByte(c.x);
            img.data[i++] = toByte(c.y);
            img.data[i++] = toByte(c.z);
        }
    return img;
}

}  // namespace glint
