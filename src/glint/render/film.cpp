#include "glint/render/film.h"

namespace glint {

Image8 toImage8(const Film& film) { return toImage8With(film, toByte); }

void FilmSums::add(const FilmSums& other) {
    for (size_t i = 0; i < sums_.size() && i < other.sums_.size(); ++i) {
        sums_[i] += other.sums_[i];
        weights_[i] += other.weights_[i];
    }
}

Film FilmSums::resolve() const {
    Film film(width_, height_);
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x) film.at(x, y) = pixelValue(sum(x, y), weight(x, y));
    return film;
}

}  // namespace glint
