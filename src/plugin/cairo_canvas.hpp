#pragma once
// Cairo drawing behind a small canvas interface, for sketch's PNG previews and stylit's
// painting sheet (PDF). The calls live in one plugin, libexemplar_cairo.so (cairo_plugin.cpp),
// the only binary of the `exemplar` command that links Cairo and its chain (pixman, fontconfig,
// freetype, X11/xcb: about 2.3 MB resident before main() in every process). libexemplar.so and
// the Python module link it in. Both sides are compiled from this header by one build;
// kPlugin.abi_version rejects a plugin from another build.

#include <cstdint>
#include <memory>
#include <string>

#include "exemplar/core/status.hpp"
#include "plugin_loader.hpp"

namespace exemplar::plugin::cairo {

/// Raise abi_version whenever the types below change.
inline constexpr PluginSpec kPlugin{"libexemplar_cairo.so", "exemplar_cairo_entry", 1, "Cairo"};

/// A Cairo surface and its context; each method is the Cairo call of the same name.
class Canvas {
public:
    virtual ~Canvas() = default;
    virtual void translate(double x, double y) = 0;
    virtual void scale(double sx, double sy) = 0;
    virtual void set_source_rgb(double r, double g, double b) = 0;
    virtual void set_source_rgba(double r, double g, double b, double a) = 0;
    virtual void paint() = 0;
    /// Round line caps and joins.
    virtual void set_round_lines() = 0;
    virtual void set_line_width(double width) = 0;
    /// The even-odd fill rule.
    virtual void set_even_odd_fill() = 0;
    virtual void new_path() = 0;
    virtual void new_sub_path() = 0;
    virtual void move_to(double x, double y) = 0;
    virtual void curve_to(double x1, double y1, double x2, double y2, double x3, double y3) = 0;
    virtual void arc(double cx, double cy, double radius, double from_rad, double to_rad) = 0;
    virtual void close_path() = 0;
    virtual void stroke() = 0;
    virtual void fill() = 0;
    /// Paints `width` x `height` pixels (0x00RRGGBB, row-major) with their top-left corner at
    /// (x, y), unfiltered (nearest); false if Cairo cannot make the image.
    virtual bool paint_image(const std::uint32_t* pixels, int width, int height, double x,
                             double y) = 0;
    /// Ends the drawing (a PDF canvas shows its page and finishes the document): empty, or
    /// Cairo's error.
    virtual std::string finish() = 0;
    /// An image canvas as a PNG file; false if it cannot be written.
    virtual bool write_png(const std::string& path) = 0;
};

/// What the plugin's entry point returns; `abi_version` first (plugin_loader.hpp).
struct Entry {
    int abi_version;
    /// An RGB24 image of `width` x `height` pixels, black until painted.
    std::unique_ptr<Canvas> (*new_image)(int width, int height);
    /// A one-page PDF of `width_pt` x `height_pt` points, appended to `*pdf` as it is written.
    std::unique_ptr<Canvas> (*new_pdf)(double width_pt, double height_pt, std::string* pdf);
};

/// The Cairo canvases: linked in, or the plugin loaded on first use. Unsupported `Cairo is not
/// available (libexemplar_cairo.so: <reason>)` without it.
Result<const Entry*> canvases();

}  // namespace exemplar::plugin::cairo
