#include "exemplar/filters/measures.hpp"

namespace exemplar {

double gradient_energy(const Image& image) {
    auto lum = [&](int x, int y) {
        const float* p = image.pixel(x, y);
        return image.channels() >= 3 ? 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2] : p[0];
    };
    double sum = 0.0;
    for (int y = 0; y + 1 < image.height(); ++y) {
        for (int x = 0; x + 1 < image.width(); ++x) {
            const double dx = lum(x + 1, y) - lum(x, y);
            const double dy = lum(x, y + 1) - lum(x, y);
            sum += dx * dx + dy * dy;
        }
    }
    const double pairs = static_cast<double>(image.width() - 1) * (image.height() - 1);
    return pairs > 0.0 ? sum / pairs : 0.0;
}

}  // namespace exemplar
