#pragma once
/// \file
/// A CPU path tracer (Embree for ray queries) that writes, per pixel, the full global
/// illumination and the light-path-expression buffers used by StyLit (Fišer et al. 2016,
/// §8.3.2), plus normals, depth, object and material ids and alpha.
///
/// Light paths are written as Heckbert's regular expressions over the events L (an area light
/// or the sky), D (a diffuse reflection), S (a glossy reflection) and E (the eye), read from the
/// light to the eye. Buffers (linear RGB unless noted; see docs/render.md):
///
/// | buffer                    | paths              | StyLit file |
/// |---------------------------|--------------------|-------------|
/// | `fullgi`                  | L.*E               | fullgi      |
/// | `direct_diffuse`          | LDE (area lights)  | dirdif      |
/// | `direct_specular`         | LSE (area lights)  | dirspc      |
/// | `indirect_diffuse`        | .*DE minus LDE     | indirb      |
/// | `diffuse_bounces`         | LD{1,2}E           | -           |
/// | `diffuse_interreflection` | L.*DDE             | -           |
///
/// `indirect_diffuse` is all light reflected diffusely towards the eye that is not direct light
/// from an area light (so it includes sky light, as the StyLit buffers do: their dirdif shadows
/// are black while their indirb is lit). Hence fullgi = direct_diffuse + direct_specular +
/// indirect_diffuse + (glossy reflections of the scene, L.+SE), exactly per sample.
///
/// Determinism: sample `s` of pixel `(x, y)` draws its random numbers from
/// KeyedRng(seed, y * width + x, s), so the result is bit-identical for any thread count.

#include <string>
#include <utility>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/core/run_context.hpp"
#include "exemplar/core/status.hpp"
#include "exemplar/render/scene.hpp"

namespace exemplar::render {

/// Options of one render.
struct RenderOptions {
    int width = 600;             ///< Image width in pixels, 1..16384. Default 600.
    int height = 456;            ///< Image height in pixels, 1..16384. Default 456.
    int samples_per_pixel = 64;  ///< Paths per pixel, 1..65536. Default 64.
    int max_bounces = 6;         ///< Reflections per path, 1..64. Default 6.
    std::uint64_t seed = 1;      ///< Seed of the per-pixel random numbers. Default 1.
};

/// Checks the options; the message names the option and its range.
Status validate(const RenderOptions& options);

/// The rendered buffers, all `width` x `height`.
struct RenderBuffers {
    Image fullgi;                   ///< RGB, linear.
    Image direct_diffuse;           ///< RGB, LDE.
    Image direct_specular;          ///< RGB, LSE.
    Image indirect_diffuse;         ///< RGB, .*DE minus LDE.
    Image diffuse_bounces;          ///< RGB, LD{1,2}E.
    Image diffuse_interreflection;  ///< RGB, L.*DDE.
    Image normal;                   ///< XYZ world-space shading normal at the pixel centre; 0 on
                                    ///< background.
    Image depth;        ///< Distance from the eye along the centre ray; 0 on background.
    Image object_id;    ///< 1-based object index at the pixel centre; 0 on background.
    Image material_id;  ///< 1-based material index; 0 on background.
    Image alpha;        ///< Fraction of samples hitting geometry, [0, 1].
    /// Channel "angle": screen direction, radians in [0, pi) counter-clockwise (x right, y up
    /// on screen), of the surface tangent perpendicular to the view ray at the pixel centre
    /// (n x d for shading normal n and ray direction d): it runs along silhouettes and along
    /// the isophotes of n.d. Undefined (0) where the surface faces the camera head-on (|n x d| <
    /// 1e-6) and on background.
    Image orientation;
    /// Channel "L": 1 on the near side of a silhouette or crease, else 0. A pixel is marked
    /// when a 4-neighbour has another object id (or is background), lies much deeper (the
    /// second difference of depth exceeds 2% of depth: a depth discontinuity, not a slanted
    /// plane), or its facet (geometric) normal differs by more than 45 degrees (a crease); of the
    /// two pixels of a discontinuity the one nearer the eye is marked.
    Image lines;

    /// Motion buffers, written by `render_frame` only (empty for `render`). Flows have channels
    /// "u", "v" in pixels (x right, y down): forward_flow of frame t maps pixel x to x + f(x)
    /// in frame t+1, backward_flow maps x to x + b(x) in frame t-1; background pixels follow
    /// the sky (infinitely far). occlusion ("occluded"): 1 where the point seen at the pixel
    /// centre is hidden (ray depth test) or off-screen in frame t+1; disocclusion: the same for
    /// frame t-1 (the point was not visible before). "Off-screen" uses the rule of
    /// exemplar/video/warp.hpp: outside -0.5 <= x <= W - 0.5, -0.5 <= y <= H - 0.5.
    Image forward_flow;
    Image backward_flow;
    Image occlusion;
    Image disocclusion;

    /// (name, image) of every non-empty buffer in the order above; names as the member names.
    std::vector<std::pair<std::string, const Image*>> layers() const;
};

/// Renders `scene`. Reports progress (stage "render", fraction of rows done) and honours
/// cancellation (ErrorCode::Cancelled) through `context`; `context.threads` 0 = all cores.
Result<RenderBuffers> render(const Scene& scene, const RenderOptions& options,
                             const RunContext& context = {});

/// How buffers are written to files.
enum class BufferFileFormat {
    Png,  ///< One 8-bit PNG per buffer; light buffers sRGB-encoded (clipped to [0, 1]), normals
          ///< as 0.5 + 0.5 n, depth divided by its maximum, ids as value / 255, alpha, lines
          ///< and occlusion masks as they are; flows and orientation (float data) as EXR.
    Exr,  ///< One float EXR per buffer, linear values as rendered.
};

/// Writes every buffer as `<folder>/<name>.png` (or .exr); the folder must exist. Atomic per file.
Status save_buffers_to_folder(const RenderBuffers& buffers, const std::string& folder,
                              BufferFileFormat format);

/// Writes every buffer as a named layer of one multi-layer float EXR (`fullgi.R`, ...,
/// `depth.Y`, ...). Atomic.
Status save_buffers_to_exr(const RenderBuffers& buffers, const std::string& path);

/// The sRGB encoding of linear values (clipped to [0, 1]), as the StyLit PNG buffers are stored.
Image encode_srgb(const Image& linear);

}  // namespace exemplar::render
