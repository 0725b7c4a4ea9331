// The painting sheet: a light grey render, white margins, marks where the layout says (black
// centre dot, white ring, black ring; two rings on the top-left mark), and PNG + PDF files.

#include "exemplar/stylit/sheet.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>

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
    const Status written = save_sheet_pdf(*sheet, pdf, PdfOptions{"letter", 0.0});
    ASSERT_TRUE(written.is_ok()) << written.message();
    std::ifstream in(pdf, std::ios::binary);
    const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    EXPECT_EQ(bytes.rfind("%PDF-", 0), 0u);
    EXPECT_NE(bytes.find("/MediaBox [ 0 0 792 612 ]"), std::string::npos);  // landscape letter
    EXPECT_TRUE(fs::exists(dir / "sheet.png"));

    // A resolution at which the sheet does not fit names the smallest that does; nothing written.
    const Status too_big = save_sheet_pdf(*sheet, (dir / "big.pdf").string(), PdfOptions{"a4", 20});
    EXPECT_FALSE(too_big.is_ok());
    EXPECT_NE(too_big.message().find("use at least"), std::string::npos) << too_big.message();
    EXPECT_FALSE(fs::exists(dir / "big.pdf"));
    EXPECT_FALSE(save_sheet_pdf(*sheet, pdf, PdfOptions{"b5", 0}).is_ok());
    std::size_t files = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++files;
    EXPECT_EQ(files, 2u);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace exemplar
