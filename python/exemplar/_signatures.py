"""Signatures and docstrings of exemplar's functions, generated from one description.

The synthesis keywords (patch_size, em_iterations, ...) come from the library's option table
(``_exemplar.option_specs()``, the table the CLI's flags, the job-file keys and docs/cli.md come
from); the other parameters are described once below. The same description gives each function
its ``inspect.signature``, its docstring and its entry in ``__init__.pyi``:

    PYTHONPATH=build/release/python /usr/bin/python3 python/tools/make_stubs.py

regenerates the stubs (with the built module on PYTHONPATH); a test keeps them equal.
"""

from __future__ import annotations

import inspect
import textwrap
from typing import Any, Callable, NamedTuple

from . import _exemplar

_REQUIRED = inspect.Parameter.empty


class Param(NamedTuple):
    name: str
    annotation: str
    doc: str
    default: Any = _REQUIRED
    positional: bool = False


_IMAGE = "Image"
_SYNTHESIS = "synthesis"  # marker: the quality/usage/vote words and the option table
_FLUID = "fluid"  # marker: the fluid option table (patch_size, temporal_weight, ...)
_NOISY = "noisy"  # marker: the noisy option table (noise, level_ratio, ...)
_NPR = "npr"  # marker: the npr option table (levels, patch_size, coherence_weight)
_BRUSH = "brush"  # marker: the line-feature brush's option table (sample_spacing, ...)
_FILL = "fill"  # marker: the area-feature fill's option table (patch_size, rotations, ...)
_RUN = [
    Param("threads", "int", "Threads; 0 = all cores. The result is the same for any count.", 0),
    Param("progress", "Callable[[Progress], bool | None] | None",
          "Called (with the GIL) with an exemplar.Progress as the run advances; returning False "
          "or raising cancels the run (the exception is re-raised, False raises "
          "exemplar.Cancelled).", None),
    Param("cancel", "CancelToken | None",
          "A CancelToken another thread may set to stop the run (exemplar.Cancelled); a "
          "progress callback that returns False sets it too.", None),
]
_WORDS = [
    Param("quality", "str",
          "Search effort: 'fast' (previews, about 2x faster), 'default' or 'best' (closer to the "
          "exemplar, about 1.7x the time); applied first, so explicit options below win.",
          "default"),
    Param("usage", "str",
          "Patch-usage strategy: 'none', 'uniform', 'error-budget' or 'occurrence'.",
          "error-budget"),
    Param("vote", "str", "Voting: 'average' or 'weighted' (weights 1/(0.01 + e/mean e)).",
          "weighted"),
]

_VERBS: dict[str, tuple[str, list[Any], str]] = {
    "stylize": (
        "Guided patch-based synthesis (image analogies A : A' :: B : B'): transfers the style "
        "exemplar onto the target the guides describe. The CLI's `exemplar stylize`, with "
        "arrays where it reads files.",
        [
            Param("style", _IMAGE, "Style exemplar A' (HxWxC; alpha is just another channel).",
                  positional=True),
            Param("guides", "Sequence[Guide]",
                  "Guide pairs (source, target[, weight[, weight_map]]) or dicts with those "
                  "keys: source on the style's grid (A_i), target on the target grid (B_i), "
                  "equal channel counts; weight >= 0 (default 1); weight_map an HxW per-pixel "
                  "multiplier on the target grid.", (), positional=True),
            Param("style_weights", "Sequence[float] | None",
                  "Weights of the style channels, one per channel, >= 0 (default 1 each).", None),
            Param("target_mask", "Image | None",
                  "Grey HxW: synthesize only where > 0.5; elsewhere keep init (needs init).",
                  None),
            Param("source_mask", "Image | None",
                  "Grey HxW on the style's grid: use only patches entirely inside (> 0.5).", None),
            Param("source_labels", "Image | None",
                  "Label map on the style's grid (HxW or HxWxC; each distinct value is one "
                  "label); with target_labels.", None),
            Param("target_labels", "Image | None",
                  "Label map on the target grid: a pixel takes only patches of its label.", None),
            Param("source_orientation", "Image | None",
                  "Angle field of the style (HxW float32, radians); with target_orientation.",
                  None),
            Param("target_orientation", "Image | None",
                  "Angle field of the target: patches are compared rotated by the difference.",
                  None),
            Param("init", "Image | None", "Initial target (the style's channels, target size).",
                  None),
            Param("init_nnf", "Image | None",
                  "Initial NNF (HxWx4 float32, as StylizeResult.nnf).", None),
            Param("size", "tuple[int, int] | None",
                  "Target size (width, height) for unguided texture synthesis; with guides or "
                  "init it must equal theirs.", None),
            _SYNTHESIS,
            *_RUN,
        ],
        "StylizeResult",
    ),
    "apply_nnf": (
        "Re-applies a correspondence field to another image on the style's grid (a 16-bit or "
        "extra-channel version of the style), voting as the synthesis did. The CLI's "
        "`exemplar apply-nnf`. Returns an array of the source's channels and dtype.",
        [
            Param("nnf", _IMAGE, "The field, HxWx4 (or x, y, angle: HxWx3) float32, as "
                  "StylizeResult.nnf.", positional=True),
            Param("source", _IMAGE, "Image to copy from, on the style's grid.", positional=True),
            Param("patch_size", "int", "Patch size the field was made with "
                  "(StylizeResult.nnf_patch_size)."),
            Param("vote_size", "int", "Central part of each patch that votes, as the run's "
                  "final_vote_size (StylizeResult.vote_size); 0 = whole patches.", 3),
            Param("vote", "str", "'average' or 'weighted', as the run.", "weighted"),
            Param("vote_coherence", "float", "Coherence weighting of the weighted vote, as the "
                  "run's vote_coherence.", 0.0),
            Param("vote_seams", "bool", "Seams blended, as the run's final_vote_seams "
                  "(StylizeResult.vote_seams).", False),
            _RUN[0],
        ],
        "numpy.ndarray",
    ),
    "stylit": (
        "StyLit: transfers a painting of an exemplar render onto a new render through both "
        "renders' light-path buffers (full render, direct diffuse, direct specular, indirect, "
        "in that order). The CLI's `exemplar stylit`; every synthesis option is accepted.",
        [
            Param("exemplar", _IMAGE, "The artist's painting, aligned to the exemplar render "
                  "(A').", positional=True),
            Param("source", "Sequence[Image] | Sequence[str] | str",
                  "Buffers of the exemplar render: arrays in guide order, or as on the CLI file "
                  "paths, one multi-layer EXR or one folder (named by preset or layers).",
                  positional=True),
            Param("target", "Sequence[Image] | Sequence[str] | str",
                  "Buffers of the target render, in the same order.", positional=True),
            Param("guidance_weight", "float",
                  "Total weight of the buffers, split equally among them (mu of Eq. 8.1), "
                  "0..100.", 2.0),
            Param("preview", "bool",
                  "Half resolution on PCA-compressed buffers (output at half size).", False),
            Param("preset", "str", "EXR layer or folder file names: 'exemplar', 'cycles' or "
                  "'arnold' (paths only).", "exemplar"),
            Param("layers", "str | None", "Comma-separated layer names instead of preset "
                  "(paths only).", None),
            _SYNTHESIS,
            *_RUN,
        ],
        "StylizeResult",
    ),
    "render": (
        "Path-traces a scene into light-path buffers (StyLit's guides). The CLI's "
        "`exemplar render`; returns the buffers as a dict of HxWxC float32 arrays (linear "
        "values, as its EXR files hold them): fullgi, direct_diffuse, direct_specular, "
        "indirect_diffuse, diffuse_bounces, diffuse_interreflection, normal, depth, object_id, "
        "material_id, alpha, orientation, lines; with frame also forward_flow, backward_flow, "
        "occlusion, disocclusion.",
        [
            Param("scene", "str", "A scene JSON file, or a built-in scene "
                  "(exemplar.builtin_scenes).", positional=True),
            Param("width", "int", "Image width in pixels, 1..16384.", 600),
            Param("height", "int", "Image height in pixels, 1..16384.", 456),
            Param("spp", "int", "Samples (paths) per pixel, 1..65536.", 64),
            Param("max_bounces", "int", "Surface reflections per path, 1..64.", 6),
            Param("seed", "int", "Seed of the random numbers.", 1),
            Param("frame", "int | None",
                  "Animation frame to render, with its motion vectors and occlusion masks "
                  "(required for an animated scene; one frame per call).", None),
            *_RUN,
        ],
        "dict[str, numpy.ndarray]",
    ),
    "animate": (
        "Stylized animation by example (TCIA, Benard et al. 2013): the analogy style_input : "
        "style_output :: frame t : output t, with the texture following the motion; painted "
        "keyframes are reproduced exactly. The CLI's `exemplar animate` for one layer, with "
        "the job file's keys as keywords (its weights as <name>_weight); returns the stylized "
        "frames, the style output's channels and dtype.",
        [
            Param("style_input", _IMAGE, "S: the style's input (the frames' channels).",
                  positional=True),
            Param("style_output", _IMAGE, "S-hat: the stylized style (any channels).",
                  positional=True),
            Param("frames", "Sequence[Image]", "The animation's frames, all of one size.",
                  positional=True),
            Param("flows", "Sequence[tuple[Image, Image]] | None",
                  "Per consecutive pair of frames, (forward flow of t, backward flow of t+1), "
                  "HxWx2 float32 in pixels (docs/video.md); None = estimate with DIS.", None),
            Param("keyframes", "Sequence[tuple[int, Image] | tuple[int, Image, Image]]",
                  "Painted keyframes (frame, image[, mask]): the style output's channels, the "
                  "frames' size; mask HxW coverage in 0..1 for a partial key.", ()),
            Param("lines", "tuple[Image, Sequence[Image]] | None",
                  "Line drawings for the line term: (on the style's grid, one per frame), dark "
                  "lines on a light background.", None),
            Param("output_weight", "float", "w_out: the style term.", 1.0),
            Param("input_weight", "float", "w_in: the guide (style input, frame).", 2.0),
            Param("temporal_weight", "float",
                  "w_tc: the previous output warped along the motion.", 1.0),
            Param("input_derivative_weight", "float",
                  "w_din: the input's change along the motion, with keyframes; 0 = use "
                  "temporal_weight there too.", 1.0),
            Param("keyframe_weight", "float",
                  "Weight of a keyframe's painted pixels when its offsets are fitted.", 4.0),
            Param("line_weight", "float", "w_dt: the line term (with lines).", 2.0),
            Param("line_max_distance", "float", "d_max of the line term, px.", 10.0),
            Param("levels", "int", "Pyramid levels of the coarse-to-fine loop, 1..8.", 4),
            Param("sweeps", "int", "Forward-backward sweep pairs per level.", 1),
            Param("backward_em_iterations", "int", "EM iterations of a backward-sweep call.", 1),
            Param("occlusion_tolerance", "float",
                  "Occlusion test tolerance, px^2; 0 = automatic (2 given flows, 8 estimated).",
                  0.0),
            Param("orientation", "bool", "Rotate patches by the structure-tensor orientation.",
                  False),
            Param("ribbons", "bool", "With keyframes, offer the keys' offsets along the motion.",
                  True),
            Param("flow_preset", "str", "DIS preset when flows are estimated: 'ultrafast', "
                  "'fast' or 'medium'.", "medium"),
            _SYNTHESIS,
            *_RUN,
        ],
        "list[numpy.ndarray]",
    ),
    "flow": (
        "Optical flow between two frames (DIS), and on request the backward flow and the "
        "occlusion mask of the first frame. The CLI's `exemplar flow`; returns a dict with "
        "'forward' (HxWx2 float32, pixels: x of from_frame maps to x + f(x) in to_frame), "
        "and 'backward' and 'occlusion' (HxW float32, 1 = fails the forward-backward test) "
        "when asked for.",
        [
            Param("from_frame", _IMAGE, "Frame t.", positional=True),
            Param("to_frame", _IMAGE, "Frame t+1 (same size).", positional=True),
            Param("backward", "bool", "Also return the backward flow t+1 -> t.", False),
            Param("occlusion", "bool", "Also return the occlusion mask of frame t.", False),
            Param("epsilon", "float", "Tolerance of the occlusion test in px^2 (squared "
                  "round-trip distance); 2 (Benard et al. 2013), 4..10 suit estimated flow.",
                  2.0),
            Param("preset", "str", "DIS preset: 'ultrafast', 'fast' or 'medium'.", "medium"),
        ],
        "dict[str, numpy.ndarray]",
    ),
    "fluid_frame": (
        "LazyFluids (Jamriska et al. 2015): synthesizes one frame of a fluid animation from an "
        "RGBA exemplar, the frame's target alpha mask and, after the first frame, the previous "
        "output and the motion that carries it here. The step `exemplar fluid` takes per frame "
        "(call it frame after frame, passing each output as the next previous_output). Returns "
        "the frame, HxWx4 RGBA with straight alpha, in the exemplar's dtype.",
        [
            Param("exemplar", _IMAGE, "Z^t: the RGBA exemplar (4 channels, straight alpha).",
                  positional=True),
            Param("target_alpha", _IMAGE, "X^t_a: the target alpha mask (HxW, values 0..1).",
                  positional=True),
            Param("previous_output", "Image | None",
                  "X^{t-1}: the previous frame's output (RGBA, target size); None = first frame "
                  "(no temporal term).", None),
            Param("previous_motion", "Image | None",
                  "F^{t-1}: forward motion from the previous frame to this one (HxWx2 float32, "
                  "pixels); required with previous_output.", None),
            Param("previous_exemplar", "Image | None",
                  "Z^{t-1}: the exemplar frame of the previous output frame; None = exemplar (a "
                  "still exemplar).", None),
            Param("motion", "Image | None",
                  "This frame's forward motion (HxWx2 float32), for motion_blur.", None),
            _FLUID,
            Param("usage", "str", "'uniform' (LazyFluids) or 'none' (plain nearest "
                  "neighbours, for comparisons).", "uniform"),
            Param("rotations", "bool",
                  "Add the exemplar rotated by 90, 180 and 270 degrees.", False),
            Param("seed", "int", "Random seed (same seed, same output).", 1),
            *_RUN,
        ],
        "numpy.ndarray",
    ),
    "fluid_simulate": (
        "Simulates the built-in `plume` scene of `exemplar fluid simulate` (2D stable fluids) "
        "into LazyFluids targets. Returns (alphas, motions): per frame an HxW float32 alpha "
        "mask and the HxWx2 float32 forward motion to the next frame, in pixels.",
        [
            Param("width", "int", "Frame width, pixels (8..8192)."),
            Param("height", "int", "Frame height, pixels (8..8192)."),
            Param("frames", "int", "Number of frames (>= 1)."),
            Param("seed", "int", "Seed of the emitters' jitter (the scene's seed).", 1),
            Param("warmup_frames", "int",
                  "Frames simulated before the first returned one (the scene's warmup_frames).",
                  0),
            *_RUN,
        ],
        "tuple[list[numpy.ndarray], list[numpy.ndarray]]",
    ),
    "noisy_frame": (
        "Color Me Noisy (Fiser et al. 2014): re-synthesizes one frame of a reference animation "
        "from a scan of a drawing medium, the frame's low frequencies following the reference "
        "and its details changing at random from frame to frame (more with a larger noise). "
        "The call `exemplar noisy` makes per frame: frame `frame` depends only on (exemplar, "
        "reference, options, seed, frame). Returns the frame at the reference's size in the "
        "exemplar's channels and dtype.",
        [
            Param("exemplar", "Image | Sequence[Image]",
                  "S: the scan of the drawing medium (1..4 channels), or a list of media of one "
                  "channel count chosen per pixel by source_map.",
                  positional=True),
            Param("reference", _IMAGE, "R_i: the reference frame (1, 3 or 4 channels).",
                  positional=True),
            Param("frame", "int", "The frame's number i (keys its randomness, as the CLI's "
                  "frame numbers do).", 0),
            _NOISY,
            Param("seed", "int", "Random seed: frame i depends only on (seed, i).", 1),
            Param("filter", "str", "Low-pass filter: 'box' or 'lanczos3'.", "box"),
            Param("noise_map", "Image | None",
                  "Per-pixel noise strength in [0, 1] scaling noise (HxW, reference size).",
                  None),
            Param("source_map", "numpy.ndarray | None",
                  "Local choice of source: HxW integer indices into the list of exemplars "
                  "(reference size; required with several).", None),
            Param("exemplar_orientation", "Image | Sequence[Image] | None",
                  "Orientation field of the exemplar (HxW float32, radians), a list with "
                  "several; with frame_orientation.", None),
            Param("frame_orientation", "Image | None",
                  "Orientation field of the frame (HxW float32, radians, reference size).",
                  None),
            *_RUN,
        ],
        "numpy.ndarray",
    ),
    "npr_frame": (
        "Image-space stippling, hatching or halftoning of a rendered animation (Image Space "
        "Texture Synthesis for 3D NPR Animation): one frame of `exemplar npr`. The pattern's "
        "coordinates are synthesized coarse to fine, following the renderer's exact motion from "
        "the previous frame's state, then thresholded by the tone with tone correction, the "
        "renderer's lines inked on top. Call it frame after frame, passing each returned state "
        "as the next call's previous (the same seed and frame numbers give the CLI's bytes). "
        "Returns (image, state): the frame, HxWx1 in the pattern's dtype (0 = ink, 1 = paper "
        "for the thresholded styles), and an exemplar.NprState.",
        [
            Param("pattern", _IMAGE, "The example pattern: a stipple, hatching or halftone "
                  "screen (grey, or RGB read as Rec. 709 luma), treated as tileable.",
                  positional=True),
            Param("buffers", "dict[str, Image]",
                  "The frame's render buffers by name, as exemplar.render(scene, frame=n) "
                  "returns them or a frame folder of `exemplar render --frames` holds them "
                  "(HxW or HxWxC). Read: the tone buffer, the orientation buffer if used, "
                  "backward_flow and disocclusion with previous, lines; others are ignored.",
                  positional=True),
            Param("previous", "NprState | None",
                  "The previous frame's state (the second value an npr_frame returned); None = "
                  "the first frame. The pattern is prepared once and reused while it stays the "
                  "same.", None),
            Param("frame", "int", "The frame's number (keys its randomness with the seed, as "
                  "the CLI's frame numbers do).", 0),
            Param("paper", "Image | None",
                  "A paper texture (the CLI's --paper): synthesized like the pattern along the "
                  "same motion, its grain shades the result and its noise erodes the boundary of "
                  "the shape in buffers['alpha'] (then read). Its state travels in the returned "
                  "NprState. None = no paper layer.", None),
            Param("style", "str",
                  "'stipple', 'halftone' (isotropic, thresholded), 'hatch' (oriented, "
                  "thresholded) or 'pattern' (the synthesized pattern, no tone).", "stipple"),
            Param("tone", "str | None",
                  "Buffer giving the tone (its luma, sRGB-encoded); None = 'direct_diffuse'. "
                  "Not for style 'pattern'.", None),
            Param("orientation", "str | None",
                  "Buffer giving the pattern's orientation (radians), or 'none'; None = "
                  "'orientation' for style 'hatch', 'none' otherwise.", None),
            Param("lines", "bool", "Ink the renderer's lines buffer (silhouettes, creases).",
                  True),
            Param("tone_correction", "bool",
                  "Blur, subtract and re-threshold so the local tone matches (s6.0.1).", True),
            _NPR,
            Param("seed", "int", "Random seed (same seed, same output).", 1),
            Param("linear_tone", "bool | None",
                  "Whether the tone buffer holds linear light (sRGB-encoded first, as the CLI "
                  "does with EXR buffers); None = float32 arrays are linear (as render() returns "
                  "them), uint8 arrays encoded (as 8-bit PNG buffers).", None),
            *_RUN,
        ],
        "tuple[numpy.ndarray, NprState]",
    ),
    "directions": (
        "Brushables' signed direction field of an exemplar (Lukac et al. 2015 s3.1): edge "
        "tangent flow from tangents whose signs were harmonized first. The CLI's "
        "`exemplar directions`; returns the angles (HxW float32, radians in (-pi, pi], "
        "counter-clockwise on screen, 0 where no direction is known), paint's "
        "source_directions.",
        [
            Param("image", _IMAGE, "The exemplar (grey from Rec. 709 luma of channels 0..2).",
                  positional=True),
            Param("radius", "float", "Radius of the edge tangent flow filter in px (1..100); "
                  "about 35 for noisy textures.", 10.0),
            Param("iterations", "int", "Edge tangent flow iterations (0..10).", 3),
            Param("gradient_sigma", "float", "Blur before the gradients in px (0..10).", 1.0),
            Param("harmonize", "bool", "Harmonize the tangents' signs (False: plain ETF, the "
                  "CLI's --no-harmonize).", True),
            _RUN[0],
        ],
        "numpy.ndarray",
    ),
    "paint": (
        "Brushables (Lukac et al. 2015): paints strokes on a canvas and fills the painted "
        "region with the exemplar's texture, its features following the strokes' directions "
        "and its boundary effects the region's edges. The CLI's `exemplar paint` with the "
        "strokes as dicts (the keys of its JSON stroke files); returns RGBA (straight alpha, "
        "transparent outside the strokes, or over canvas), the source's dtype.",
        [
            Param("source", _IMAGE, "The exemplar: RGBA (alpha = its shape) or RGB.",
                  positional=True),
            Param("strokes", "Sequence[dict[str, Any]]",
                  "Strokes in order: {'points': Nx2 (x, y in canvas px), 'width': brush "
                  "diameter in px (default 40), 'comb': True to only re-direct painted pixels, "
                  "'label': segment id with source_labels (default 0)}.",
                  positional=True),
            Param("width", "int | None", "Canvas width in px (or canvas's).", None),
            Param("height", "int | None", "Canvas height in px (or canvas's).", None),
            Param("canvas", "Image | None", "Background to paint over (RGB or RGBA).", None),
            Param("source_mask", "Image | None",
                  "Shape mask of the exemplar (HxW, inside where > 0.5); default alpha > 0.",
                  None),
            Param("source_directions", "Image | None",
                  "Direction field of the exemplar (HxW float32 angles, as directions() "
                  "returns); default directions(source).", None),
            Param("source_labels", "Image | None",
                  "Segmentation of the exemplar into several textures (HxW integer segment "
                  "ids): a stroke paints only with the segment of its 'label'.", None),
            Param("shape_weight", "float", "Weight lambda of the Shape Hint against the "
                  "colour distance (0 = off, ..1000).", 25.0),
            Param("edge_extent", "float", "How deep boundary effects reach into the texture, "
                  "px: the Shape Hint's radius (1..256).", 16.0),
            Param("shape_bins", "int", "Bins on the Shape Hint's ring (4..32).", 8),
            Param("alpha_weight", "float", "Weight of alpha against each colour channel "
                  "(0..100).", 3.0),
            Param("vote_coherence", "float", "Coherence range sigma_c^2 of the vote in px^2 "
                  "(0 = off, ..100).", 2.0),
            Param("vote_histogram", "float", "Colour-histogram weight of the vote: rarer "
                  "exemplar colours are not averaged away (0 = off, ..100).", 1.0),
            Param("usage", "str", "Patch usage: 'none' (the paper's EM) or 'uniform' (keeps "
                  "sparse flecks; 'error-budget', 'occurrence' as in stylize).", "none"),
            Param("patch_size", "int", "Patch width in px (odd, 3..15).", 5),
            Param("seed", "int", "Random seed.", 1),
            *_RUN,
        ],
        "numpy.ndarray",
    ),
    "brush": (
        "Painting by Feature's line-feature brush (Lukac et al. 2013): a line feature picked "
        "in any palette image by a rough stroke along it (snapped onto its edge) is painted "
        "along new paths of any length without visible repetition. The CLI's `exemplar brush` "
        "with the feature and the paths as stroke dicts (the keys of its JSON stroke files); "
        "returns RGBA (straight alpha, transparent outside the paths, or over canvas), the "
        "palette's dtype.",
        [
            Param("palette", _IMAGE, "The feature palette: any image (grey, RGB, RGBA).",
                  positional=True),
            Param("feature", "dict[str, Any]",
                  "The line feature: one rough stroke along it, {'points': Nx2 (x, y in palette "
                  "px), 'width': the selection's width = the patch size (default 40)}.",
                  positional=True),
            Param("paths", "Sequence[dict[str, Any]]",
                  "The paths to paint, in order: {'points': Nx2 (x, y in canvas px), 'width': "
                  "brush width in px (default 40)}.", positional=True),
            Param("width", "int | None", "Canvas width in px (or canvas's).", None),
            Param("height", "int | None", "Canvas height in px (or canvas's).", None),
            Param("canvas", "Image | None", "Background to paint over (RGB or RGBA).", None),
            Param("brush_width", "float",
                  "Width of every painted stroke in px (0 = each path's width; at most 4096); "
                  "the feature is scaled by brush width / feature width.", 0.0),
            Param("snap", "bool", "Snap the feature's rough path onto the palette's edge "
                  "(False: the CLI's --no-snap).", True),
            Param("walk", "str", "Walk through the feature: 'randomized', or 'looping' and "
                  "'dp' (comparison modes).", "randomized"),
            Param("seed", "int", "Random seed of the walk.", 1),
            _BRUSH,
            *_RUN,
        ],
        "numpy.ndarray",
    ),
    "fill": (
        "Painting by Feature's area-feature fill (Lukac et al. 2013): the target region of the "
        "canvas is filled with the texture of the source region of the palette (content-aware "
        "synthesis over pre-rotated copies of the region), meeting what the canvas holds "
        "around it. The CLI's `exemplar fill`; regions are images, inside where the mean "
        "colour is above 0.5. Returns the canvas's channels (RGBA without a canvas), the "
        "palette's dtype; pixels outside the target region are the canvas's.",
        [
            Param("palette", _IMAGE, "The feature palette: any image (grey, RGB, RGBA).",
                  positional=True),
            Param("source_region", _IMAGE, "White where the palette's texture is picked "
                  "(palette size).", positional=True),
            Param("target_region", _IMAGE, "White where the canvas is filled (canvas size).",
                  positional=True),
            Param("canvas", "Image | None",
                  "What is painted already (grey, RGB, RGBA): kept outside the region, "
                  "continued across its border; None = the region filled free-standing on a "
                  "transparent RGBA image (target region's size).", None),
            Param("usage", "str", "Patch usage: 'uniform' (keeps sparse features), 'none' (the "
                  "chapter's plain EM), 'error-budget' or 'occurrence'.", "uniform"),
            Param("seed", "int", "Random seed.", 1),
            _FILL,
            *_RUN,
        ],
        "numpy.ndarray",
    ),
    "vectorize_style": (
        "Painting by Feature's vector image stylization (Lukac et al. 2013): the stroked paths "
        "of an SVG drawing are painted with line features and its filled shapes with area "
        "features picked in a palette image, as a style palette file assigns them (by stroke "
        "and fill colour or class; docs/feature.md). The CLI's `exemplar vectorize-style`; "
        "returns RGBA uint8 (straight alpha), the drawing's size or width wide.",
        [
            Param("drawing", "str", "The path of the SVG drawing.", positional=True),
            Param("palette", "str", "The path of the style palette file (.json).",
                  positional=True),
            Param("width", "int", "Canvas width in px, the height in the drawing's proportion "
                  "(0 = the drawing's size).", 0),
            Param("walk", "str", "Walk through the line features: 'randomized', 'looping' or "
                  "'dp'.", "randomized"),
            Param("usage", "str", "Patch usage of the fills: 'uniform', 'none', 'error-budget' "
                  "or 'occurrence'.", "uniform"),
            Param("seed", "int", "Random seed of the walks and fills.", 1),
            _BRUSH,
            _FILL,
            *_RUN,
        ],
        "numpy.ndarray",
    ),
    "beautify": (
        "ShipShape: beautifies a sketch stroke by stroke (lines, arcs, snapping, parallel, "
        "perpendicular, equal length, copies, mirrors, steps, offsets), each against the strokes "
        "before it, keeping the most likely suggestion. The CLI's `exemplar beautify`; returns "
        "the beautified SVG, the report and the last stroke's suggestions.",
        [
            Param("drawing", "str | Sequence[numpy.ndarray]",
                  "SVG text, the path of an .svg file, or strokes as Nx2 arrays of points "
                  "(polylines, in view pixels), in drawing order.", positional=True),
            Param("max_suggestions", "int", "Suggestions per stroke, 1..100 (the paper's N).",
                  10),
            Param("fit", "float",
                  "Refit strokes drawn as polylines (3 or more straight pieces) as smooth "
                  "Bezier paths within this many view px before beautifying, 0..100; 0 keeps "
                  "them as drawn.", 0.0),
        ],
        "BeautifyResult",
    ),
}


def _verb_table_params(specs: list[dict[str, Any]], required: tuple[str, ...] = ()
                       ) -> list[Param]:
    """A verb's own option table (fluid, noisy, npr, brush, fill) as keyword parameters."""
    params = []
    for spec in specs:
        unit = f" {spec['unit']}" if spec["unit"] else ""
        low, high = (int(spec["min"]), int(spec["max"])) if spec["type"] == "int" \
            else (spec["min"], spec["max"])
        doc = f"{spec['doc'].rstrip('.')}. Range {low}..{high}{unit}."
        default = _REQUIRED if spec["name"] in required else spec["default"]
        params.append(Param(spec["name"], spec["type"], doc, default))
    return params


def _table_params(verb: str) -> list[Param]:
    # animate starts from its own engine defaults and owns `levels` (the solver's); stylize and
    # stylit from the default quality preset.
    defaults = _exemplar._animate_defaults() if verb == "animate" else _exemplar._stylize_defaults()
    params = []
    for spec in _exemplar.option_specs():
        if verb == "animate" and spec["name"] == "levels":
            continue
        unit = f" {spec['unit']}" if spec["unit"] else ""
        doc = f"{spec['doc']} Range {spec['min']}..{spec['max']}{unit}."
        params.append(Param(spec["name"], spec["type"], doc,
                            defaults.get(spec["name"], spec["default"])))
    return params


def _words(verb: str) -> list[Param]:
    if verb == "animate":  # its job file has no vote key
        usage = _exemplar._animate_defaults()["usage"]
        return [_WORDS[0], _WORDS[1]._replace(default=usage)]
    return _WORDS


def _params(verb: str) -> list[Param]:
    params = []
    for param in _VERBS[verb][1]:
        if param == _SYNTHESIS:
            params += _words(verb) + _table_params(verb)
        elif param == _FLUID:
            params += _verb_table_params(_exemplar._fluid_option_specs())
        elif param == _NOISY:
            # noise has no default on the CLI either: the noise level is the user's choice.
            noisy = _verb_table_params(_exemplar._noisy_option_specs(), required=("noise",))
            params += sorted(noisy, key=lambda p: p.default is not _REQUIRED)
        elif param == _NPR:
            params += _verb_table_params(_exemplar._npr_option_specs())
        elif param == _BRUSH:
            params += _verb_table_params(_exemplar._feature_brush_option_specs())
        elif param == _FILL:
            params += _verb_table_params(_exemplar._feature_fill_option_specs())
        else:
            params.append(param)
    return params


def signature(verb: str) -> inspect.Signature:
    """The Python signature of `verb`: positional parameters, then keyword-only ones."""
    return inspect.Signature(
        [inspect.Parameter(p.name,
                           inspect.Parameter.POSITIONAL_OR_KEYWORD if p.positional
                           else inspect.Parameter.KEYWORD_ONLY,
                           default=p.default, annotation=p.annotation)
         for p in _params(verb)],
        return_annotation=_VERBS[verb][2])


def docstring(verb: str) -> str:
    """The docstring of `verb`: its summary, then one entry per parameter."""
    # Flags such as finest-em-iterations are not broken at their hyphens.
    lines = textwrap.wrap(_VERBS[verb][0], 88, break_on_hyphens=False) + ["", "Parameters:"]
    for p in _params(verb):
        default = "" if p.default is _REQUIRED else f", default {p.default!r}"
        lines.append(f"  {p.name} ({p.annotation}{default})")
        lines += textwrap.wrap(p.doc, 88, initial_indent="      ", subsequent_indent="      ",
                               break_on_hyphens=False)
    lines += ["", f"Returns {_VERBS[verb][2]}. Errors raise exemplar.Error subclasses with the "
              "library's one-line message."]
    return "\n".join(lines)


def decorate(function: Callable[..., Any]) -> Callable[..., Any]:
    """Gives a verb's wrapper its generated signature and docstring."""
    function.__signature__ = signature(function.__name__)  # type: ignore[attr-defined]
    function.__doc__ = docstring(function.__name__)
    return function


_STUB_HEAD = '''\
# Generated by python/tools/make_stubs.py from the library's option table; do not edit.
from typing import Any, Callable, Sequence, TypedDict, Union

import numpy
import numpy.typing

Image = numpy.typing.NDArray[Union[numpy.float32, numpy.uint8]]
Guide = Union[tuple[Image, Image], tuple[Image, Image, float], tuple[Image, Image, float, Image],
              dict[str, Any]]

__version__: str

class Error(Exception): ...
class InvalidArgumentError(Error, ValueError): ...
class IoError(Error, OSError): ...
class UnsupportedError(Error, ValueError): ...
class Cancelled(Error): ...
class InternalError(Error, RuntimeError): ...

class Progress:
    stage: str
    level: int
    levels: int
    iteration: int
    iterations: int
    fraction: float

class CancelToken:
    def __init__(self) -> None: ...
    def cancel(self) -> None: ...
    @property
    def cancelled(self) -> bool: ...

class StylizeResult:
    image: numpy.ndarray
    nnf: numpy.ndarray
    error: numpy.ndarray
    nnf_patch_size: int
    vote_size: int
    vote_seams: bool
    vote_coherence: float
    guide_channels: int
    explained_variance: float
    unlabelled_levels: list[int]

class NprState:
    frame: int
    levels: int
    coords: list[numpy.ndarray]

class BeautifyResult:
    svg: str
    paths: list[str]
    strokes: list[dict[str, Any]]
    relation_counts: dict[str, int]
    suggestions: list[dict[str, Any]]

class OptionSpec(TypedDict):
    name: str
    doc: str
    unit: str
    type: str
    min: float
    max: float
    default: float

builtin_scenes: tuple[str, ...]

def option_specs() -> list[OptionSpec]: ...
def load_image(path: str) -> numpy.ndarray: ...
def save_image(image: Image, path: str) -> None: ...
'''


def stubs() -> str:
    """The text of __init__.pyi."""
    out = [_STUB_HEAD]
    for verb in _VERBS:
        params = _params(verb)
        out.append(f"def {verb}(")
        star = False
        for p in params:
            if not p.positional and not star:
                out.append("    *,")
                star = True
            default = "" if p.default is _REQUIRED else f" = {p.default!r}"
            out.append(f"    {p.name}: {p.annotation}{default},")
        out.append(f") -> {_VERBS[verb][2]}:")
        body = textwrap.indent(docstring(verb), "    ")
        out.append(f'    """{body.lstrip()}\n    """\n')
    return "\n".join(out)
