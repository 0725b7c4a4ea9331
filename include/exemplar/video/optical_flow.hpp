#pragma once
/// \file
/// Optical flow estimation between two frames with OpenCV's DIS optical flow (Kroeger et al.
/// 2016, "Fast Optical Flow using Dense Inverse Search"), for real footage that comes without
/// rendered velocity fields.
///
/// Frames are reduced to 8-bit grey for DIS: 1-2 channels use channel 0, 3 or more the Rec. 709
/// luma of channels 0..2; values are clamped to [0, 1] first (HDR frames should be tone-mapped
/// by the caller). The result is a flow field as in exemplar/io/flow_io.hpp: 2 channels
/// "u", "v", and f(x) maps pixel x of `from` to x + f(x) in `to`.

#include "exemplar/core/image.hpp"
#include "exemplar/core/status.hpp"

namespace exemplar::video {

/// DIS quality/speed presets (cv::DISOpticalFlow::PRESET_*).
enum class FlowPreset {
    UltraFast,
    Fast,
    Medium,  ///< Default: the most accurate preset.
};

/// Options of `estimate_flow`.
struct FlowOptions {
    FlowPreset preset = FlowPreset::Medium;  ///< DIS preset. Default Medium.
};

/// Parses "ultrafast", "fast" or "medium"; InvalidArgument naming the word otherwise.
Result<FlowPreset> parse_flow_preset(const std::string& name);

/// Dense flow from `from` to `to`. InvalidArgument if either frame is empty, the sizes differ
/// or a frame is smaller than 16x16 (DIS's patches need room). Deterministic: the same inputs
/// give the same bytes.
Result<Image> estimate_flow(const Image& from, const Image& to, const FlowOptions& options = {});

/// Forward flow (t → t+1) and backward flow (t+1 → t) of a frame pair.
struct FlowPair {
    Image forward;   ///< On the grid of frame t: x ↦ x + forward(x) in frame t+1.
    Image backward;  ///< On the grid of frame t+1: x ↦ x + backward(x) in frame t.
};

/// Both directions of `estimate_flow` (two independent DIS runs).
Result<FlowPair> estimate_flow_pair(const Image& frame, const Image& next,
                                    const FlowOptions& options = {});

}  // namespace exemplar::video
