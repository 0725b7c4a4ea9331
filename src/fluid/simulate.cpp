// Stable fluids (Stam 1999, "Stable fluids", SIGGRAPH): semi-Lagrangian advection, implicit
// diffusion, pressure projection; with buoyancy and vorticity confinement (Fedkiw, Stam and
// Jensen 2001, "Visual simulation of smoke"). Deviations from Stam's paper: a staggered (MAC)
// grid instead of a collocated one, so that the divergence the pressure solve removes is the one
// measured (the collocated central differences leave a checkerboard); conjugate gradients with a
// MIC(0) preconditioner, warm-started from the previous frame's pressure,
// instead of Gauss-Seidel relaxation for the pressure; second-order (midpoint) back-tracing; an
// open border (pressure 0 outside) instead of closed walls, so that a plume leaves the frame.

#include "exemplar/fluid/simulate.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "exemplar/core/parallel.hpp"
#include "exemplar/core/rng.hpp"

namespace exemplar::fluid {

namespace {

// Rows per parallel task: enough pixels that scheduling does not dominate the small loops.
int row_grain(int width) {
    return std::max(1, 16384 / std::max(width, 1));
}

// The simulator's projection: largest divergence left per frame (px/frame, against velocities of
// pixels per frame), and a cap on the conjugate-gradient iterations.
constexpr float kProjectionTolerance = 1e-3f;
constexpr int kProjectionMaxIterations = 1000;

// Jacobi iterations of the implicit diffusion (Stam's solver uses 20).
constexpr int kDiffusionIterations = 20;

// Bilinear sample of a w × h grid at grid coordinates (fx, fy), clamped to the grid.
float sample_clamped(const std::vector<float>& grid, int w, int h, float fx, float fy) {
    fx = std::clamp(fx, 0.0f, static_cast<float>(w - 1));
    fy = std::clamp(fy, 0.0f, static_cast<float>(h - 1));
    const int x0 = std::min(static_cast<int>(fx), std::max(w - 2, 0));
    const int y0 = std::min(static_cast<int>(fy), std::max(h - 2, 0));
    const int x1 = std::min(x0 + 1, w - 1), y1 = std::min(y0 + 1, h - 1);
    const float ax = fx - static_cast<float>(x0), ay = fy - static_cast<float>(y0);
    auto at = [&](int x, int y) { return grid[static_cast<std::size_t>(y) * w + x]; };
    return (1 - ay) * ((1 - ax) * at(x0, y0) + ax * at(x1, y0)) +
           ay * ((1 - ax) * at(x0, y1) + ax * at(x1, y1));
}

// Bilinear sample of channel c of a cell-centred image; cells outside the image read 0.
float sample_zero_outside(const Image& image, float x, float y, int c) {
    if (!(std::isfinite(x) && std::isfinite(y))) return 0.0f;
    const float fx = std::floor(x), fy = std::floor(y);
    const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
    const float ax = x - fx, ay = y - fy;
    auto at = [&](int xx, int yy) {
        if (xx < 0 || yy < 0 || xx >= image.width() || yy >= image.height()) return 0.0f;
        return image.at(xx, yy, c);
    };
    return (1 - ay) * ((1 - ax) * at(x0, y0) + ax * at(x0 + 1, y0)) +
           ay * ((1 - ax) * at(x0, y0 + 1) + ax * at(x0 + 1, y0 + 1));
}

// Midpoint back-trace of position (x, y) over one frame.
void trace_back(const MacVelocity& velocity, float x, float y, float& bx, float& by) {
    float u = 0, v = 0;
    velocity.sample(x, y, u, v);
    float um = 0, vm = 0;
    velocity.sample(x - 0.5f * u, y - 0.5f * v, um, vm);
    bx = x - um;
    by = y - vm;
}

// Implicit diffusion (I − k∆) x = x0 on a w × h grid by Jacobi iterations (deterministic:
// every iteration reads the previous one only), borders clamped.
void diffuse(std::vector<float>& grid, int w, int h, float k, int threads) {
    if (k <= 0.0f) return;
    const std::vector<float> x0 = grid;
    std::vector<float> next(grid.size());
    for (int it = 0; it < kDiffusionIterations; ++it) {
        parallel_for(
            0, h, threads,
            [&](int y) {
                for (int x = 0; x < w; ++x) {
                    auto at = [&](int xx, int yy) {
                        xx = std::clamp(xx, 0, w - 1);
                        yy = std::clamp(yy, 0, h - 1);
                        return grid[static_cast<std::size_t>(yy) * w + xx];
                    };
                    const std::size_t i = static_cast<std::size_t>(y) * w + x;
                    next[i] =
                        (x0[i] + k * (at(x - 1, y) + at(x + 1, y) + at(x, y - 1) + at(x, y + 1))) /
                        (1 + 4 * k);
                }
            },
            row_grain(w));
        grid.swap(next);
    }
}

// Sum of per-row partial sums in row order: the same result for any thread count.
double ordered_sum(std::vector<double>& rows) {
    double s = 0.0;
    for (double r : rows) s += r;
    return s;
}

Status field_error(const std::string& name, double value, const char* rule) {
    return invalid_argument(name + ": " + std::to_string(value) + " is invalid (must be " + rule +
                            ")");
}

}  // namespace

MacVelocity::MacVelocity(int w, int h)
    : width(w),
      height(h),
      u(static_cast<std::size_t>(w + 1) * h, 0.0f),
      v(static_cast<std::size_t>(w) * (h + 1), 0.0f) {}

void MacVelocity::sample(float x, float y, float& out_u, float& out_v) const {
    out_u = sample_clamped(u, width + 1, height, x + 0.5f, y);
    out_v = sample_clamped(v, width, height + 1, x, y + 0.5f);
}

Image MacVelocity::cell_centred() const {
    Image out(width, height, 2);
    out.set_channel_names({"u", "v"});
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            out.at(x, y, 0) = 0.5f * (u_at(x, y) + u_at(x + 1, y));
            out.at(x, y, 1) = 0.5f * (v_at(x, y) + v_at(x, y + 1));
        }
    }
    return out;
}

float divergence(const MacVelocity& velocity, int x, int y) {
    return velocity.u_at(x + 1, y) - velocity.u_at(x, y) + velocity.v_at(x, y + 1) -
           velocity.v_at(x, y);
}

Image advect(const Image& field, const MacVelocity& velocity, int threads) {
    Image out(field.width(), field.height(), field.channels());
    out.set_channel_names(field.channel_names());
    parallel_for(
        0, field.height(), threads,
        [&](int y) {
            for (int x = 0; x < field.width(); ++x) {
                float bx = 0, by = 0;
                trace_back(velocity, static_cast<float>(x), static_cast<float>(y), bx, by);
                for (int c = 0; c < field.channels(); ++c) {
                    out.at(x, y, c) = sample_zero_outside(field, bx, by, c);
                }
            }
        },
        row_grain(field.width()));
    return out;
}

int project(MacVelocity& vel, const std::vector<std::uint8_t>& solid, float tolerance,
            int max_iterations, int threads, std::vector<double>* pressure_io) {
    const int w = vel.width, h = vel.height;
    const auto n = static_cast<std::size_t>(w) * h;
    auto is_solid = [&](int x, int y) {
        return !solid.empty() && solid[static_cast<std::size_t>(y) * w + x] != 0;
    };
    // Walls: faces touching a solid cell carry no flow.
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x <= w; ++x) {
            if ((x > 0 && is_solid(x - 1, y)) || (x < w && is_solid(x, y))) vel.u_at(x, y) = 0;
        }
    }
    for (int y = 0; y <= h; ++y) {
        for (int x = 0; x < w; ++x) {
            if ((y > 0 && is_solid(x, y - 1)) || (y < h && is_solid(x, y))) vel.v_at(x, y) = 0;
        }
    }
    // A p = b with A = −∆ over the fluid cells (neighbours outside the domain: p = 0, counted on
    // the diagonal; solid neighbours: no face, not counted) and b = −div. The residual b − A p
    // is minus the divergence left after the update below.
    std::vector<float> diag(n, 0.0f);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            if (is_solid(x, y)) continue;
            int d = 0;
            d += (x == 0 || !is_solid(x - 1, y)) ? 1 : 0;
            d += (x == w - 1 || !is_solid(x + 1, y)) ? 1 : 0;
            d += (y == 0 || !is_solid(x, y - 1)) ? 1 : 0;
            d += (y == h - 1 || !is_solid(x, y + 1)) ? 1 : 0;
            diag[static_cast<std::size_t>(y) * w + x] = static_cast<float>(d);
        }
    }
    auto apply_a = [&](const std::vector<double>& p, std::vector<double>& out) {
        parallel_for(
            0, h, threads,
            [&](int y) {
                for (int x = 0; x < w; ++x) {
                    const std::size_t i = static_cast<std::size_t>(y) * w + x;
                    if (diag[i] == 0.0f) {
                        out[i] = 0.0;
                        continue;
                    }
                    double s = diag[i] * p[i];
                    if (x > 0 && !is_solid(x - 1, y)) s -= p[i - 1];
                    if (x < w - 1 && !is_solid(x + 1, y)) s -= p[i + 1];
                    if (y > 0 && !is_solid(x, y - 1)) s -= p[i - static_cast<std::size_t>(w)];
                    if (y < h - 1 && !is_solid(x, y + 1)) s -= p[i + static_cast<std::size_t>(w)];
                    out[i] = s;
                }
            },
            row_grain(w));
    };
    std::vector<double> rows(static_cast<std::size_t>(h));
    auto dot = [&](const std::vector<double>& a, const std::vector<double>& b) {
        parallel_for(
            0, h, threads,
            [&](int y) {
                double s = 0.0;
                const std::size_t row = static_cast<std::size_t>(y) * w;
                for (int x = 0; x < w; ++x) s += a[row + x] * b[row + x];
                rows[static_cast<std::size_t>(y)] = s;
            },
            row_grain(w));
        return ordered_sum(rows);
    };
    auto max_abs = [](const std::vector<double>& a) {
        double m = 0.0;
        for (double value : a) m = std::max(m, std::abs(value));
        return m;
    };

    // Modified incomplete Cholesky preconditioner, MIC(0) (Bridson, "Fluid simulation for
    // computer graphics", §5.4): sequential sweeps, so deterministic; it cuts the iterations
    // several-fold against plain CG.
    auto fluid_cell = [&](int x, int y) {
        return x >= 0 && y >= 0 && x < w && y < h && !is_solid(x, y);
    };
    std::vector<double> precon(n, 0.0);
    constexpr double kTau = 0.97, kSigma = 0.25;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * w + x;
            if (diag[i] == 0.0f) continue;
            double e = diag[i];
            if (fluid_cell(x - 1, y)) {
                const double pl = precon[i - 1];
                e -= pl * pl;
                if (fluid_cell(x - 1, y + 1)) e -= kTau * pl * pl;
            }
            if (fluid_cell(x, y - 1)) {
                const double pu = precon[i - static_cast<std::size_t>(w)];
                e -= pu * pu;
                if (fluid_cell(x + 1, y - 1)) e -= kTau * pu * pu;
            }
            if (e < kSigma * diag[i]) e = diag[i];
            precon[i] = 1.0 / std::sqrt(e);
        }
    }
    std::vector<double> q(n, 0.0);
    auto apply_preconditioner = [&](const std::vector<double>& in, std::vector<double>& out) {
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                const std::size_t i = static_cast<std::size_t>(y) * w + x;
                if (diag[i] == 0.0f) {
                    q[i] = 0.0;
                    continue;
                }
                double t = in[i];
                if (fluid_cell(x - 1, y)) t += precon[i - 1] * q[i - 1];
                if (fluid_cell(x, y - 1)) {
                    const std::size_t u = i - static_cast<std::size_t>(w);
                    t += precon[u] * q[u];
                }
                q[i] = t * precon[i];
            }
        }
        for (int y = h - 1; y >= 0; --y) {
            for (int x = w - 1; x >= 0; --x) {
                const std::size_t i = static_cast<std::size_t>(y) * w + x;
                if (diag[i] == 0.0f) {
                    out[i] = 0.0;
                    continue;
                }
                double t = q[i];
                if (fluid_cell(x + 1, y)) t += precon[i] * out[i + 1];
                if (fluid_cell(x, y + 1)) t += precon[i] * out[i + static_cast<std::size_t>(w)];
                out[i] = t * precon[i];
            }
        }
    };

    std::vector<double> p(n, 0.0), r(n, 0.0), z(n, 0.0), d(n, 0.0), ad(n, 0.0);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            if (!is_solid(x, y)) r[static_cast<std::size_t>(y) * w + x] = -divergence(vel, x, y);
        }
    }
    if (pressure_io != nullptr && pressure_io->size() == n) {
        // Warm start: r = b − A p.
        p = *pressure_io;
        for (std::size_t i = 0; i < n; ++i) {
            if (diag[i] == 0.0f) p[i] = 0.0;
        }
        apply_a(p, ad);
        for (std::size_t i = 0; i < n; ++i) r[i] -= ad[i];
    }
    apply_preconditioner(r, z);
    d = z;
    double rz = dot(r, z);
    int it = 0;
    for (; it < max_iterations && max_abs(r) > tolerance; ++it) {
        apply_a(d, ad);
        const double dad = dot(d, ad);
        if (dad <= 0.0) break;
        const double alpha = rz / dad;
        parallel_for(
            0, h, threads,
            [&](int y) {
                const std::size_t row = static_cast<std::size_t>(y) * w;
                for (std::size_t i = row; i < row + static_cast<std::size_t>(w); ++i) {
                    p[i] += alpha * d[i];
                    r[i] -= alpha * ad[i];
                }
            },
            row_grain(w));
        apply_preconditioner(r, z);
        const double rz_next = dot(r, z);
        const double beta = rz_next / rz;
        rz = rz_next;
        parallel_for(
            0, h, threads,
            [&](int y) {
                const std::size_t row = static_cast<std::size_t>(y) * w;
                for (std::size_t i = row; i < row + static_cast<std::size_t>(w); ++i) {
                    d[i] = z[i] + beta * d[i];
                }
            },
            row_grain(w));
    }
    if (pressure_io != nullptr) *pressure_io = p;
    // Subtract the pressure gradient on every face between non-solid cells (or the border).
    auto pressure = [&](int x, int y) {
        if (x < 0 || y < 0 || x >= w || y >= h) return 0.0;
        return p[static_cast<std::size_t>(y) * w + x];
    };
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x <= w; ++x) {
            if ((x > 0 && is_solid(x - 1, y)) || (x < w && is_solid(x, y))) continue;
            vel.u_at(x, y) -= static_cast<float>(pressure(x, y) - pressure(x - 1, y));
        }
    }
    for (int y = 0; y <= h; ++y) {
        for (int x = 0; x < w; ++x) {
            if ((y > 0 && is_solid(x, y - 1)) || (y < h && is_solid(x, y))) continue;
            vel.v_at(x, y) -= static_cast<float>(pressure(x, y) - pressure(x, y - 1));
        }
    }
    return it;
}

FluidScene plume_scene(int width, int height) {
    FluidScene scene;
    scene.width = width;
    scene.height = height;
    Emitter e;
    e.x_px = 0.5f * static_cast<float>(width);
    e.y_px = 0.88f * static_cast<float>(height);
    e.radius_px = std::max(3.0f, 0.06f * static_cast<float>(std::min(width, height)));
    e.rate = 0.35f;
    e.velocity_y = -0.015f * static_cast<float>(height);
    scene.emitters.push_back(e);
    scene.buoyancy = 0.001f * static_cast<float>(height);
    return scene;
}

Status validate(const FluidScene& scene) {
    if (scene.width < 8 || scene.width > 8192) return field_error("width", scene.width, "8..8192");
    if (scene.height < 8 || scene.height > 8192) {
        return field_error("height", scene.height, "8..8192");
    }
    auto check = [](const std::string& name, float value, bool ok, const char* rule) {
        return ok && std::isfinite(value) ? Status::ok() : field_error(name, value, rule);
    };
    for (std::size_t i = 0; i < scene.emitters.size(); ++i) {
        const Emitter& e = scene.emitters[i];
        const std::string at = "emitters[" + std::to_string(i) + "].";
        for (const Status& s : {check(at + "position", e.x_px, true, "finite"),
                                check(at + "position", e.y_px, true, "finite"),
                                check(at + "radius", e.radius_px, e.radius_px > 0, "> 0"),
                                check(at + "rate", e.rate, e.rate >= 0, ">= 0"),
                                check(at + "velocity", e.velocity_x, true, "finite"),
                                check(at + "velocity", e.velocity_y, true, "finite")}) {
            if (!s.is_ok()) return s;
        }
    }
    for (std::size_t i = 0; i < scene.obstacles.size(); ++i) {
        const Obstacle& o = scene.obstacles[i];
        const std::string at = "obstacles[" + std::to_string(i) + "].";
        for (const Status& s : {check(at + "position", o.x_px, true, "finite"),
                                check(at + "position", o.y_px, true, "finite"),
                                check(at + "radius", o.radius_px, o.radius_px > 0, "> 0")}) {
            if (!s.is_ok()) return s;
        }
    }
    for (const Status& s : {check("gravity", scene.gravity_x, true, "finite"),
                            check("gravity", scene.gravity_y, true, "finite"),
                            check("buoyancy", scene.buoyancy, scene.buoyancy >= 0, ">= 0"),
                            check("vorticity", scene.vorticity, scene.vorticity >= 0, ">= 0"),
                            check("viscosity", scene.viscosity, scene.viscosity >= 0, ">= 0"),
                            check("diffusion", scene.diffusion, scene.diffusion >= 0, ">= 0"),
                            check("density-decay", scene.density_decay,
                                  scene.density_decay >= 0 && scene.density_decay <= 1, "0..1"),
                            check("turbulence", scene.turbulence,
                                  scene.turbulence >= 0 && scene.turbulence <= 1, "0..1")}) {
        if (!s.is_ok()) return s;
    }
    if (scene.warmup_frames < 0 || scene.warmup_frames > 100000) {
        return field_error("warmup-frames", scene.warmup_frames, "0..100000");
    }
    return Status::ok();
}

FluidSimulator::FluidSimulator(FluidScene scene)
    : scene_(std::move(scene)),
      density_(scene_.width, scene_.height, 1),
      velocity_(scene_.width, scene_.height),
      solid_(static_cast<std::size_t>(scene_.width) * scene_.height, 0) {
    density_.set_channel_names({"A"});
    for (int y = 0; y < scene_.height; ++y) {
        for (int x = 0; x < scene_.width; ++x) {
            for (const Obstacle& o : scene_.obstacles) {
                const float dx = static_cast<float>(x) - o.x_px;
                const float dy = static_cast<float>(y) - o.y_px;
                if (dx * dx + dy * dy <= o.radius_px * o.radius_px) {
                    solid_[static_cast<std::size_t>(y) * scene_.width + x] = 1;
                }
            }
        }
    }
    apply_emitters();
}

void FluidSimulator::apply_emitters() {
    const int w = scene_.width, h = scene_.height;
    for (std::size_t k = 0; k < scene_.emitters.size(); ++k) {
        const Emitter& e = scene_.emitters[k];
        const int x0 = std::max(0, static_cast<int>(std::floor(e.x_px - e.radius_px - 1)));
        const int x1 = std::min(w - 1, static_cast<int>(std::ceil(e.x_px + e.radius_px + 1)));
        const int y0 = std::max(0, static_cast<int>(std::floor(e.y_px - e.radius_px - 1)));
        const int y1 = std::min(h - 1, static_cast<int>(std::ceil(e.y_px + e.radius_px + 1)));
        for (int y = y0; y <= y1; ++y) {
            for (int x = x0; x <= x1; ++x) {
                const float dist =
                    std::hypot(static_cast<float>(x) - e.x_px, static_cast<float>(y) - e.y_px);
                const float cover = std::clamp(e.radius_px - dist + 0.5f, 0.0f, 1.0f);
                if (cover <= 0.0f) continue;
                KeyedRng rng(scene_.seed, static_cast<std::uint64_t>(frame_), k,
                             static_cast<std::uint64_t>(y) * w + x);
                const float jitter = 1.0f + scene_.turbulence * (2.0f * rng.uniform() - 1.0f);
                float& d = density_.at(x, y, 0);
                d = std::min(1.0f, d + cover * e.rate * jitter);
            }
        }
    }
}

void FluidSimulator::update_velocity(int threads) {
    const int w = scene_.width, h = scene_.height;
    MacVelocity& vel = velocity_;
    // Forces: gravity, buoyancy (up, y down), vorticity confinement.
    for (float& u : vel.u) u += scene_.gravity_x;
    for (float& v : vel.v) v += scene_.gravity_y;
    for (int y = 1; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const float d = 0.5f * (density_.at(x, y - 1, 0) + density_.at(x, y, 0));
            vel.v_at(x, y) -= scene_.buoyancy * d;
        }
    }
    if (scene_.vorticity > 0.0f) {
        const Image c = vel.cell_centred();
        Image curl(w, h, 1);
        for (int y = 1; y < h - 1; ++y) {
            for (int x = 1; x < w - 1; ++x) {
                curl.at(x, y, 0) = 0.5f * (c.at(x + 1, y, 1) - c.at(x - 1, y, 1)) -
                                   0.5f * (c.at(x, y + 1, 0) - c.at(x, y - 1, 0));
            }
        }
        Image force(w, h, 2);
        for (int y = 2; y < h - 2; ++y) {
            for (int x = 2; x < w - 2; ++x) {
                const float gx =
                    0.5f * (std::abs(curl.at(x + 1, y, 0)) - std::abs(curl.at(x - 1, y, 0)));
                const float gy =
                    0.5f * (std::abs(curl.at(x, y + 1, 0)) - std::abs(curl.at(x, y - 1, 0)));
                const float len = std::sqrt(gx * gx + gy * gy) + 1e-5f;
                const float omega = curl.at(x, y, 0);
                force.at(x, y, 0) = scene_.vorticity * (gy / len) * omega;
                force.at(x, y, 1) = -scene_.vorticity * (gx / len) * omega;
            }
        }
        for (int y = 0; y < h; ++y) {
            for (int x = 1; x < w; ++x) {
                vel.u_at(x, y) += 0.5f * (force.at(x - 1, y, 0) + force.at(x, y, 0));
            }
        }
        for (int y = 1; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                vel.v_at(x, y) += 0.5f * (force.at(x, y - 1, 1) + force.at(x, y, 1));
            }
        }
    }
    // Self-advection of each face's component.
    MacVelocity next(w, h);
    parallel_for(
        0, h, threads,
        [&](int y) {
            for (int x = 0; x <= w; ++x) {
                float bx = 0, by = 0;
                trace_back(vel, static_cast<float>(x) - 0.5f, static_cast<float>(y), bx, by);
                float u = 0, v = 0;
                vel.sample(bx, by, u, v);
                next.u_at(x, y) = u;
            }
        },
        row_grain(w));
    parallel_for(
        0, h + 1, threads,
        [&](int y) {
            for (int x = 0; x < w; ++x) {
                float bx = 0, by = 0;
                trace_back(vel, static_cast<float>(x), static_cast<float>(y) - 0.5f, bx, by);
                float u = 0, v = 0;
                vel.sample(bx, by, u, v);
                next.v_at(x, y) = v;
            }
        },
        row_grain(w));
    vel = std::move(next);
    diffuse(vel.u, w + 1, h, scene_.viscosity, threads);
    diffuse(vel.v, w, h + 1, scene_.viscosity, threads);
    // Emitters impose their velocity on the faces inside them.
    for (const Emitter& e : scene_.emitters) {
        const float r2 = e.radius_px * e.radius_px;
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x <= w; ++x) {
                const float dx = static_cast<float>(x) - 0.5f - e.x_px;
                const float dy = static_cast<float>(y) - e.y_px;
                if (dx * dx + dy * dy <= r2) vel.u_at(x, y) = e.velocity_x;
            }
        }
        for (int y = 0; y <= h; ++y) {
            for (int x = 0; x < w; ++x) {
                const float dx = static_cast<float>(x) - e.x_px;
                const float dy = static_cast<float>(y) - 0.5f - e.y_px;
                if (dx * dx + dy * dy <= r2) vel.v_at(x, y) = e.velocity_y;
            }
        }
    }
    project(vel, solid_, kProjectionTolerance, kProjectionMaxIterations, threads, &pressure_);
}

void FluidSimulator::advance_density(int threads) {
    density_ = advect(density_, velocity_, threads);
    std::vector<float> d(density_.data().begin(), density_.data().end());
    diffuse(d, scene_.width, scene_.height, scene_.diffusion, threads);
    for (std::size_t i = 0; i < d.size(); ++i) {
        density_.data()[i] = solid_[i] ? 0.0f : std::clamp(d[i] * scene_.density_decay, 0.0f, 1.0f);
    }
    ++frame_;
    apply_emitters();
}

Status simulate(const FluidScene& scene, int frames, const FrameSink& on_frame,
                const RunContext& context) {
    if (Status s = validate(scene); !s.is_ok()) return s;
    if (frames < 1 || frames > 1000000) {
        return invalid_argument("frames: " + std::to_string(frames) +
                                " is invalid (must be 1..1000000)");
    }
    FluidSimulator sim(scene);
    for (int i = 0; i < scene.warmup_frames; ++i) {
        if (context.cancelled()) return cancelled();
        sim.update_velocity(context.threads);
        sim.advance_density(context.threads);
    }
    for (int f = 0; f < frames; ++f) {
        if (context.cancelled()) return cancelled();
        sim.update_velocity(context.threads);
        if (Status s = on_frame(f, sim.density(), sim.motion()); !s.is_ok()) return s;
        sim.advance_density(context.threads);
        context.report({"simulate", 0, 1, f + 1, frames, static_cast<double>(f + 1) / frames});
    }
    return Status::ok();
}

}  // namespace exemplar::fluid
