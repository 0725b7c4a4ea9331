#pragma once
/// \file
/// A small 2D stable-fluids solver (Stam 1999, "Stable fluids") for designing LazyFluids
/// targets without a third-party simulator: per frame an alpha mask (the smoke density) and the
/// forward motion to the next frame.
///
/// Conventions: one grid cell per pixel, cell (x, y) centred at pixel (x, y); one time step per
/// frame; velocities in pixels per frame, x right, y down. Velocities live on a staggered (MAC)
/// grid so that the projection's divergence is exactly the one the pressure solve removes.
/// The image border is open (pressure 0 outside, smoke leaves the frame); obstacles are solid
/// discs (velocity 0 on their faces, no smoke inside). Deterministic for any thread count.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/core/run_context.hpp"
#include "exemplar/core/status.hpp"

namespace exemplar::fluid {

/// Where smoke is injected: a disc that adds density and sets the velocity inside it.
struct Emitter {
    float x_px = 0.0f;       ///< Centre, pixels.
    float y_px = 0.0f;       ///< Centre, pixels.
    float radius_px = 8.0f;  ///< Disc radius, pixels (> 0).
    /// Density added per frame inside the disc (density is clamped to [0, 1]; ≥ 0).
    float rate = 0.5f;
    float velocity_x = 0.0f;  ///< Velocity imposed inside the disc, px/frame.
    float velocity_y = 0.0f;  ///< Velocity imposed inside the disc, px/frame (negative = up).
};

/// A solid disc: no flow through it, no smoke inside.
struct Obstacle {
    float x_px = 0.0f;
    float y_px = 0.0f;
    float radius_px = 10.0f;  ///< > 0.
};

/// A fluid scene: domain, sources, forces. Defaults make a gentle rising plume.
struct FluidScene {
    int width = 0;   ///< Pixels (8..8192).
    int height = 0;  ///< Pixels (8..8192).
    std::vector<Emitter> emitters;
    std::vector<Obstacle> obstacles;
    float gravity_x = 0.0f;  ///< Constant acceleration, px/frame² (applied everywhere).
    float gravity_y = 0.0f;  ///< Constant acceleration, px/frame².
    /// Upward acceleration per unit density, px/frame² (hot smoke rises; ≥ 0).
    float buoyancy = 0.08f;
    /// Vorticity confinement strength ε (Fedkiw et al. 2001), keeps small swirls alive (≥ 0).
    float vorticity = 0.3f;
    /// Kinematic viscosity, px²/frame (implicit diffusion of the velocity; 0 = none, ≥ 0).
    float viscosity = 0.0f;
    /// Diffusion of the density, px²/frame (implicit; 0 = none, ≥ 0).
    float diffusion = 0.0f;
    /// Fraction of the density kept per frame (1 = none lost; 0..1).
    float density_decay = 0.995f;
    /// Frames simulated before the first written frame (lets the plume develop; ≥ 0).
    int warmup_frames = 0;
    /// Random jitter of the emitters' rates, so that plumes are not symmetric (0..1).
    float turbulence = 0.3f;
    std::uint64_t seed = 1;  ///< Seed of the jitter.
};

/// The built-in `plume` scene for a width × height domain: one emitter near the bottom centre,
/// buoyancy and vorticity confinement.
FluidScene plume_scene(int width, int height);

/// Checks sizes and ranges; the message names the field (`emitters[1].radius: -2 is invalid
/// (must be > 0)`).
Status validate(const FluidScene& scene);

/// Velocity on a staggered grid: `u` on the vertical faces ((width+1) × height, face i between
/// cells i−1 and i, at x = i − 0.5), `v` on the horizontal faces (width × (height+1), at
/// y = j − 0.5). Pixels per frame.
struct MacVelocity {
    int width = 0;
    int height = 0;
    std::vector<float> u;
    std::vector<float> v;

    MacVelocity() = default;
    MacVelocity(int w, int h);
    float& u_at(int i, int j) { return u[static_cast<std::size_t>(j) * (width + 1) + i]; }
    float u_at(int i, int j) const { return u[static_cast<std::size_t>(j) * (width + 1) + i]; }
    float& v_at(int i, int j) { return v[static_cast<std::size_t>(j) * width + i]; }
    float v_at(int i, int j) const { return v[static_cast<std::size_t>(j) * width + i]; }
    /// Bilinear velocity at a position in pixels (clamped to the grid).
    void sample(float x, float y, float& out_u, float& out_v) const;
    /// Velocity at the cell centres: 2 channels `u`, `v` (the motion field format).
    Image cell_centred() const;
};

/// Divergence of cell (x, y): u(x+1) − u(x) + v(y+1) − v(y), per frame.
float divergence(const MacVelocity& velocity, int x, int y);

/// Semi-Lagrangian advection of a cell-centred image (any channels) over one frame:
/// out(x) = field(x − velocity(x)), bilinear; samples outside the domain read 0.
Image advect(const Image& field, const MacVelocity& velocity, int threads = 0);

/// Pressure projection: removes the divergence of every fluid cell by solving the 5-point
/// Poisson equation with MIC(0)-preconditioned conjugate gradients (open border: pressure 0
/// outside; `solid` cells, one byte per cell or empty, are walls with zero normal velocity). Stops
/// when the largest remaining divergence is below `tolerance` or after `max_iterations`. Returns
/// the iterations. `pressure` (optional, one value per cell) is the solve's start and receives its
/// solution: the previous frame's pressure is a close start, which saves most iterations.
int project(MacVelocity& velocity, const std::vector<std::uint8_t>& solid, float tolerance = 1e-4f,
            int max_iterations = 2000, int threads = 0, std::vector<double>* pressure = nullptr);

/// The solver: state (density, velocity) and one step per frame.
class FluidSimulator {
public:
    /// The scene must be valid (see validate()).
    explicit FluidSimulator(FluidScene scene);

    /// Computes the velocity that moves frame `frame()` to the next one: emitters, forces
    /// (gravity, buoyancy, vorticity confinement), self-advection, viscosity, projection.
    void update_velocity(int threads = 0);
    /// Moves the density along the current velocity, diffuses, decays and injects the emitters:
    /// the next frame.
    void advance_density(int threads = 0);

    /// Current density in [0, 1] (1 channel `A`): the frame's alpha mask.
    const Image& density() const { return density_; }
    const MacVelocity& velocity() const { return velocity_; }
    /// Motion of the current frame to the next (2 channels u, v, px/frame): the cell-centred
    /// velocity after update_velocity().
    Image motion() const { return velocity_.cell_centred(); }
    int frame() const { return frame_; }

private:
    void apply_emitters();
    FluidScene scene_;
    Image density_;
    MacVelocity velocity_;
    std::vector<std::uint8_t> solid_;
    std::vector<double> pressure_;  // the last projection's, the next one's start
    int frame_ = 0;
};

/// Called per simulated frame with its number (0-based), its alpha mask (density, 1 channel) and
/// its forward motion to the next frame (2 channels, px/frame). A non-ok status stops the run.
using FrameSink = std::function<Status(int frame, const Image& alpha, const Image& motion)>;

/// Runs `scene` for its warm-up and then `frames` frames, handing each to `on_frame` (which
/// writes it: frames stream, memory does not grow with their number). Errors: the scene's
/// validation, `frames` < 1, cancellation (checked once per frame), or the sink's.
Status simulate(const FluidScene& scene, int frames, const FrameSink& on_frame,
                const RunContext& context = {});

}  // namespace exemplar::fluid
