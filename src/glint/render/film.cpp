#include "glint/render/film.h"

namespace glint {

Image8 toImage8(const Film& film) { return toImage8With(film, toByte); }

}  // namespace glint
