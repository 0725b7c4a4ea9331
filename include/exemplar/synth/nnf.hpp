#pragma once
/// \file
/// Nearest-neighbour field: for every target pixel, the centre of the source patch it copies,
/// the rotation applied to that patch, and the patch distance.

#include <cstdint>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/core/status.hpp"
#include "exemplar/synth/options.hpp"

namespace exemplar {

/// One NNF entry. A target offset d maps to source position (x, y) + Rot(angle_rad) d.
/// x = y = -1 marks a target pixel that is not a patch centre (outside the dilated target
/// mask); such entries do not vote. Every other pixel is one, and a patch over the border of
/// either image reads that image's border pixels repeated.
struct Match {
    std::int32_t x = 0;      ///< Source patch centre, x.
    std::int32_t y = 0;      ///< Source patch centre, y.
    float angle_rad = 0.0f;  ///< Rotation from target to source patch coordinates.
    /// Patch distance (weighted SSD) of this assignment as found by the last search; the
    /// weighted vote derives its weights from it.
    float error = 0.0f;
};

/// A field of matches, one per target pixel, row-major.
class Nnf {
public:
    Nnf() = default;
    Nnf(int width, int height) : width_(width), height_(height), m_(pixel_count()) {}

    int width() const { return width_; }
    int height() const { return height_; }
    bool empty() const { return m_.empty(); }
    std::size_t pixel_count() const {
        return static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
    }
    Match& at(int x, int y) { return m_[static_cast<std::size_t>(y) * width_ + x]; }
    const Match& at(int x, int y) const { return m_[static_cast<std::size_t>(y) * width_ + x]; }
    Match& operator[](std::size_t i) { return m_[i]; }
    const Match& operator[](std::size_t i) const { return m_[i]; }
    std::vector<Match>& matches() { return m_; }
    const std::vector<Match>& matches() const { return m_; }

private:
    int width_ = 0;
    int height_ = 0;
    std::vector<Match> m_;
};

/// NNF as a 4-channel float image (x, y, angle_rad, error), channel names "x","y","angle","error".
/// This is the on-disk form (`--save-nnf`, EXR).
Image nnf_to_image(const Nnf& nnf);

/// Inverse of nnf_to_image. Fails if the image does not have 3 or 4 channels or holds
/// non-integral or negative source coordinates (other than the -1, -1 "no match" marker).
Result<Nnf> nnf_from_image(const Image& image);

/// The field of a finer pyramid level from a coarser one (as the engine carries its field between
/// its levels): each fine pixel takes the match of the nearest coarse pixel, scaled to the fine
/// source (`fine_source_width` x `fine_source_height`; the coarse field refers to a
/// `coarse_source_width` x `coarse_source_height` source), keeping its offset within the patch.
/// Entries with x = -1 stay "no match". Matches may fall outside the fine source by rounding;
/// the engine repairs such entries of an initial field (SynthesisInput::initial_nnf) with random
/// ones, so clamp them if the field is used elsewhere. Rows run on up to `threads` threads (0 = all
/// cores); the field is the same for any count.
Nnf upsample_nnf(const Nnf& coarse, int coarse_source_width, int coarse_source_height,
                 int fine_width, int fine_height, int fine_source_width, int fine_source_height,
                 int threads = 1);

/// Re-applies an NNF to another source image (e.g. a 16-bit or extra-channel version of the
/// style): every target pixel becomes the (weighted) average of the overlapping `patch_size`
/// patches, or of their central `vote_size` pixels (0 = whole patches), each read from `source`
/// at its match (rotated, nearest sample), exactly as the synthesis voted (use
/// SynthesisResult::nnf_patch_size, SynthesisResult::vote_size and the run's vote mode; the
/// weights come from the stored errors and, with `vote_coherence` > 0, the matches' coherence as
/// SynthesisOptions::vote_coherence; `vote_seams` as SynthesisResult::vote_seams). Source reads
/// beyond its border are clamped; every match must lie inside `source`.
Result<Image> apply_nnf(const Nnf& nnf, const Image& source, int patch_size,
                        VoteMode vote = VoteMode::Weighted, int threads = 0, int vote_size = 0,
                        float vote_coherence = SynthesisOptions{}.vote_coherence,
                        bool vote_seams = false);

}  // namespace exemplar
