// The painting sheet: a light grey render, white margins, marks where the layout says (black
// centre dot, white ring, black ring; two rings on the top-left mark), and PNG + PDF files.

#include "exemplar/stylit/sheet.hpp"

#include <gtest/gtest.h>
#include <poppler-document.h>
#include <poppler-image.h>
#include <poppler-page-renderer.h>
#include <poppler-page.h>
#include <unistd.h>
#include <zlib.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>

#include "exemplar/stylit/align.hpp"
#include "stylit_test_data.hpp"

namespace exemplar {
namespace {

namespace fs = std::filesystem;
using testing::grey_at;
using testing::load_example;

TEST(Sheet, MarksSitWhereTheLayoutSays) {
    const Image render = load_example("source_fullgi.png");
    const SheetLayout layout = sheet_layout(render.width(), render.height());
    EXPECT_EQ(layout.mark_radius_px, 21.0);  // 4.5% of 456
    const Image light = low_contrast(render, 0.72f, 0.95f);
    auto sheet = make_sheet(light, layout);
    ASSERT_TRUE(sheet.ok()) << sheet.status().message();
    EXPECT_EQ(sheet->width(), 600 + 2 * layout.margin_px);
    EXPECT_EQ(sheet->channels(), 1);

    // The render is light grey, the paper white.
    for (int y = 0; y < render.height(); y += 9) {
        for (int x = 0; x < render.width(); x += 9) {
            const float v = sheet->at(x + layout.margin_px, y + layout.margin_px, 0);
            ASSERT_GE(v, 0.72f - 1e-6f);
            ASSERT_LE(v, 0.95f + 1e-6f);
        }
    }
    EXPECT_EQ(sheet->at(layout.margin_px / 2, sheet->height() / 2, 0), 1.0f);

    const auto centres = layout.mark_centres();
    const double r = layout.mark_radius_px;
    for (std::size_t m = 0; m < 4; ++m) {
        const double cx = centres[m].x + layout.margin_px, cy = centres[m].y + layout.margin_px;
        const auto at = [&](double dx) {
            return grey_at(*sheet, static_cast<int>(std::lround(cx + dx * r)),
                           static_cast<int>(std::lround(cy)));
        };
        EXPECT_LT(at(0.0), 0.05f) << "mark " << m << ": centre dot";
        EXPECT_LT(at(0.9), 0.05f) << "mark " << m << ": outer ring";
        EXPECT_GT(at(1.3), 0.95f) << "mark " << m << ": paper outside";
        // Plain marks: white between 0.3 and 0.6 r; the top-left one is black at 0.5 r.
        if (m == 0) {
            EXPECT_LT(at(0.5), 0.05f);
            EXPECT_GT(at(0.7), 0.95f);
        } else {
            EXPECT_GT(at(0.45), 0.95f) << "mark " << m;
        }
    }
    // Marks stay outside the render.
    EXPECT_LT(centres[0].x + r, -0.5);
    EXPECT_GT(centres[2].y - r, render.height() - 0.5);
}

TEST(Sheet, WritesPngAndPdf) {
    const fs::path dir =
        fs::temp_directory_path() / ("exemplar_sheet_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const Image render = load_example("source_fullgi.png", 2);
    auto sheet = make_sheet(low_contrast(render, 0.72f, 0.95f),
                            sheet_layout(render.width(), render.height()));
    ASSERT_TRUE(sheet.ok());
    const std::string pdf = (dir / "sheet.pdf").string();
    ASSERT_TRUE(save_image(*sheet, (dir / "sheet.png").string()).is_ok());
    const SheetLayout layout = sheet_layout(render.width(), render.height());
    const Status written =
        save_sheet_pdf(low_contrast(render, 0.72f, 0.95f), layout, pdf, PdfOptions{"letter", 0.0});
    ASSERT_TRUE(written.is_ok()) << written.message();
    std::ifstream in(pdf, std::ios::binary);
    const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    EXPECT_EQ(bytes.rfind("%PDF-", 0), 0u);
    EXPECT_NE(bytes.find("/MediaBox [ 0 0 792 612 ]"), std::string::npos);  // landscape letter
    EXPECT_TRUE(fs::exists(dir / "sheet.png"));

    // A resolution at which the sheet does not fit names the smallest that does; nothing written.
    const Image light = low_contrast(render, 0.72f, 0.95f);
    const Status too_big =
        save_sheet_pdf(light, layout, (dir / "big.pdf").string(), PdfOptions{"a4", 20});
    EXPECT_FALSE(too_big.is_ok());
    EXPECT_NE(too_big.message().find("use at least"), std::string::npos) << too_big.message();
    EXPECT_FALSE(fs::exists(dir / "big.pdf"));
    EXPECT_FALSE(save_sheet_pdf(light, layout, pdf, PdfOptions{"b5", 0}).is_ok());
    EXPECT_FALSE(save_sheet_pdf(render, sheet_layout(10, 10), pdf, PdfOptions{}).is_ok());
    std::size_t files = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++files;
    EXPECT_EQ(files, 2u);
    fs::remove_all(dir);
}

std::string read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The decompressed (Flate) streams of a PDF, concatenated: Cairo compresses page contents.
std::string inflated_streams(const std::string& pdf) {
    std::string out;
    for (std::size_t at = pdf.find("stream"); at != std::string::npos;
         at = pdf.find("stream", at + 1)) {
        if (at >= 3 && pdf.compare(at - 3, 3, "end") == 0) continue;
        std::size_t begin = at + 6;
        if (pdf[begin] == '\r') ++begin;
        if (pdf[begin] == '\n') ++begin;
        const std::size_t end = pdf.find("endstream", begin);
        if (end == std::string::npos) break;
        z_stream z{};
        if (inflateInit(&z) != Z_OK) continue;
        z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(pdf.data() + begin));
        z.avail_in = static_cast<uInt>(end - begin);
        char buffer[16384];
        int status = Z_OK;
        while (status == Z_OK) {
            z.next_out = reinterpret_cast<Bytef*>(buffer);
            z.avail_out = sizeof buffer;
            status = inflate(&z, Z_NO_FLUSH);
            out.append(buffer, sizeof buffer - z.avail_out);
        }
        inflateEnd(&z);
        out += '\n';
    }
    return out;
}

// Occurrences of the operator `op` (a whitespace-separated token) in a content stream.
std::size_t count_operator(const std::string& content, const std::string& op) {
    std::istringstream tokens(content);
    std::size_t count = 0;
    for (std::string token; tokens >> token;) count += token == op ? 1 : 0;
    return count;
}

// The PDF draws the marks as vector paths and only the render as an image, and a rasterized
// print of it (poppler) still aligns: align finds the marks and maps the page back onto the
// render.
TEST(Sheet, PdfMarksAreVectorPathsThatAlignFinds) {
    const fs::path dir =
        fs::temp_directory_path() / ("exemplar_sheet_vector_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string pdf = (dir / "sheet.pdf").string();
    const Image light = low_contrast(load_example("source_fullgi.png", 2), 0.72f, 0.95f);
    const SheetLayout layout = sheet_layout(light.width(), light.height());
    ASSERT_TRUE(save_sheet_pdf(light, layout, pdf, PdfOptions{"a4", 0.0}).is_ok());

    const std::string content = inflated_streams(read_file(pdf));
    // Every ring is two circles, every dot one: 5 circles on the top-left mark, 3 on each other,
    // each at least 4 Bezier curves ("c"), one even-odd fill ("f*") per black band (3 + 3 x 2).
    EXPECT_GE(count_operator(content, "c"), 14u * 4u);
    EXPECT_EQ(count_operator(content, "f*"), 9u);
    EXPECT_EQ(count_operator(content, "Do"), 1u) << "one image: the render";

    std::unique_ptr<poppler::document> document(poppler::document::load_from_file(pdf));
    ASSERT_TRUE(document != nullptr);
    std::unique_ptr<poppler::page> page(document->create_page(0));
    ASSERT_TRUE(page != nullptr);
    poppler::page_renderer renderer;
    renderer.set_render_hint(poppler::page_renderer::antialiasing, true);
    renderer.set_image_format(poppler::image::format_argb32);
    const poppler::image raster = renderer.render_page(page.get(), 100.0, 100.0);
    ASSERT_TRUE(raster.is_valid());
    Image scan(raster.width(), raster.height(), 3);
    for (int y = 0; y < raster.height(); ++y) {
        const char* row =
            raster.const_data() + static_cast<std::size_t>(y) * raster.bytes_per_row();
        for (int x = 0; x < raster.width(); ++x) {
            std::uint32_t argb = 0;  // native-endian 0xAARRGGBB, opaque
            std::memcpy(&argb, row + 4 * static_cast<std::size_t>(x), sizeof argb);
            for (int c = 0; c < 3; ++c)
                scan.at(x, y, c) = static_cast<float>((argb >> (16 - 8 * c)) & 0xffu) / 255.0f;
        }
    }
    auto aligned = align_scan(scan, layout);
    ASSERT_TRUE(aligned.ok()) << aligned.status().message();
    double sum = 0.0;
    for (int y = 0; y < light.height(); ++y) {
        for (int x = 0; x < light.width(); ++x)
            sum += std::abs(grey_at(aligned->image, x, y) - light.at(x, y, 0));
    }
    const double mean_error = sum / static_cast<double>(light.pixel_count());
    std::printf("printed at 100 dpi (%dx%d px): aligned render within %.4f\n", raster.width(),
                raster.height(), mean_error);
    EXPECT_LT(mean_error, 0.01);  // measured 0.0015 (8-bit image, bilinear resampling)
    fs::remove_all(dir);
}

}  // namespace
}  // namespace exemplar
