#include "exemplar/filters/measures.hpp"

namespace exemplar {

double gradient_energy(const Image& image, const Image& region) {
    auto lum = [&](int x, int y) {
        const float* p = image.pixel(x, y);
        return image.channels() >= 3 ? 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2] : p[0];
    };
    auto inside = [&](int x, int y) { return region.empty() || region.at(x, y, 0) > 0.5f; };
    double sum = 0.0;
    double pairs = 0.0;
    for (int y = 0; y + 1 < image.height(); ++y) {
        for (int x = 0; x + 1 < image.width(); ++x) {
            if (!inside(x, y) || !inside(x + 1, y) || !inside(x, y + 1)) continue;
            pairs += 1.0;
            const double dx = lum(x + 1, y) - lum(x, y);
            const double dy = lum(x, y + 1) - lum(x, y);
            sum += dx * dx + dy * dy;
        }
    }
    return pairs > 0.0 ? sum / pairs : 0.0;
}

}  // namespace exemplar
