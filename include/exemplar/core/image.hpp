#pragma once
/// \file
/// The float image used everywhere in exemplar.
///
/// API conventions (all modules):
/// - Pixels are 32-bit floats, **interleaved**: channel `c` of pixel `(x, y)` is stored at
///   `data()[(y * width + x) * channels + c]`. Rows are contiguous, no padding.
/// - `(0, 0)` is the top-left pixel; x grows to the right, y downwards. Angles are in radians,
///   counter-clockwise in image space as seen on screen (i.e. with y pointing down, a positive
///   angle turns +x towards -y).
/// - 8/16-bit files are normalized to [0, 1] when loaded; float files keep their values.
/// - Channel names are optional metadata ("R", "G", "B", "A", "diffuse.R", ...); an image with
///   no names gets defaults from `default_channel_names`.
/// - Functions taking a `threads` argument use 0 = all cores, 1 = run inline on the caller.

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace exemplar {

/// Read-only, non-owning view of an interleaved float image (any row stride, in floats).
struct ConstImageView {
    const float* data = nullptr;
    int width = 0;
    int height = 0;
    int channels = 0;
    std::size_t row_stride = 0;  ///< Floats between the starts of consecutive rows.

    const float* pixel(int x, int y) const {
        return data + static_cast<std::size_t>(y) * row_stride +
               static_cast<std::size_t>(x) * static_cast<std::size_t>(channels);
    }
};

/// Owning interleaved float image with any number of channels.
class Image {
public:
    Image() = default;
    /// Creates a `width` x `height` image with `channels` channels, every value set to `fill`.
    Image(int width, int height, int channels, float fill = 0.0f);

    int width() const { return width_; }
    int height() const { return height_; }
    int channels() const { return channels_; }
    bool empty() const { return width_ == 0 || height_ == 0 || channels_ == 0; }
    std::size_t pixel_count() const {
        return static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
    }
    std::size_t size() const { return data_.size(); }

    float* pixel(int x, int y) { return data_.data() + index(x, y); }
    const float* pixel(int x, int y) const { return data_.data() + index(x, y); }
    float& at(int x, int y, int c) { return data_[index(x, y) + static_cast<std::size_t>(c)]; }
    float at(int x, int y, int c) const { return data_[index(x, y) + static_cast<std::size_t>(c)]; }

    std::span<float> data() { return data_; }
    std::span<const float> data() const { return data_; }

    ConstImageView view() const {
        return {data_.data(), width_, height_, channels_,
                static_cast<std::size_t>(width_) * static_cast<std::size_t>(channels_)};
    }

    /// Channel names; always `channels()` entries (defaults if never set).
    const std::vector<std::string>& channel_names() const { return names_; }
    /// Sets channel names; `names.size()` must equal `channels()`.
    void set_channel_names(std::vector<std::string> names);

    bool same_size(const Image& other) const {
        return width_ == other.width_ && height_ == other.height_;
    }

private:
    std::size_t index(int x, int y) const {
        return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                static_cast<std::size_t>(x)) *
               static_cast<std::size_t>(channels_);
    }

    int width_ = 0;
    int height_ = 0;
    int channels_ = 0;
    std::vector<float> data_;
    std::vector<std::string> names_;
};

/// Default names: 1 → Y; 2 → Y,A; 3 → R,G,B; 4 → R,G,B,A; otherwise c0, c1, ...
std::vector<std::string> default_channel_names(int channels);

/// Copies channels [first, first + count) into a new image (names kept).
Image extract_channels(const Image& image, int first, int count);

/// Copies the listed channels, in that order, into a new image (names kept); the image itself
/// when the list is all of its channels in order.
Image select_channels(const Image& image, std::span<const int> channels);

/// Stacks the channels of same-sized images into one image (names concatenated).
/// All images must have the same width and height (checked).
Image concat_channels(const std::vector<const Image*>& images);

/// Index of the channel called `name`, or -1.
int find_channel(const Image& image, const std::string& name);

/// True if every value is finite (no NaN or infinity).
bool all_finite(const Image& image);

/// "WxH", the size as messages give it.
std::string size_str(const Image& image);

}  // namespace exemplar
