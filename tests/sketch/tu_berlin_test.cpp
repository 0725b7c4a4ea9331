// Every TU-Berlin sketch (tests/data/strokes/tu-berlin, CC BY 4.0, Eitz, Hays and Alexa 2012)
// replayed stroke by stroke: no stroke moves further than a bound relative to its size, and the
// relations enforced are reported.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>

#include "exemplar/sketch/beautify.hpp"
#include "exemplar/sketch/svg.hpp"

namespace exemplar::sketch {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> sketches() {
    std::vector<std::string> files;
    const fs::path root = fs::path(EXEMPLAR_TEST_DATA_DIR) / "strokes" / "tu-berlin";
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
        if (entry.path().extension() == ".svg") files.push_back(entry.path().string());
    }
    std::sort(files.begin(), files.end());
    return files;
}

// A stroke may move (Fréchet distance) by at most 15% of its size (bounding-box diagonal) plus
// the snapping radius (10 view px); the median stroke by less than 5 view px.
constexpr double kRelativeBound = 0.15;
constexpr double kMedianBoundPx = 5.0;
constexpr double kAbsoluteBoundPx = 10.0;

TEST(SketchTuBerlin, EverySketchStaysCloseToTheInputAndReportsRelations) {
    const std::vector<std::string> files = sketches();
    ASSERT_EQ(files.size(), 15u);
    std::map<std::string, int> totals;
    std::vector<double> moved_px;
    for (const std::string& file : files) {
        SCOPED_TRACE(file);
        auto drawing = load_svg(file);
        ASSERT_TRUE(drawing.ok()) << drawing.status().message();
        ASSERT_GT(drawing->paths.size(), 2u);
        auto result = replay(drawing->paths, drawing->pixels_per_unit);
        ASSERT_TRUE(result.ok()) << result.status().message();
        ASSERT_EQ(result->strokes.size(), drawing->paths.size());
        int relations = 0;
        for (std::size_t i = 0; i < result->strokes.size(); ++i) {
            const StrokeResult& s = result->strokes[i];
            const double bound =
                kRelativeBound * s.size + kAbsoluteBoundPx / drawing->pixels_per_unit;
            EXPECT_LE(s.moved, bound)
                << "stroke " << i << " moved " << s.moved << " (size " << s.size << ")";
            moved_px.push_back(s.moved * drawing->pixels_per_unit);
            for (const Relation& r : s.chosen.relations()) {
                ++relations;
                ++totals[r.rule];
                EXPECT_FALSE(r.detail.empty());
            }
        }
        EXPECT_GT(relations, 0) << "no relation enforced in " << file;
    }
    std::sort(moved_px.begin(), moved_px.end());
    ASSERT_FALSE(moved_px.empty());
    EXPECT_LT(moved_px[moved_px.size() / 2], kMedianBoundPx);
    // Across the set, the common relations of hand-drawn sketches all occur.
    for (const char* rule : {"line", "arc", "endpoint"}) EXPECT_GT(totals[rule], 0) << rule;
    for (const auto& [rule, count] : totals) std::cout << "  " << rule << ": " << count << '\n';
}

// The bundled demo drawing (examples/sketch/house.svg): each stroke gets the relation it was
// drawn to show.
TEST(SketchExamples, HouseDemoEnforcesTheIntendedRelations) {
    auto drawing = load_svg(std::string(EXEMPLAR_SOURCE_DIR) + "/examples/sketch/house.svg");
    ASSERT_TRUE(drawing.ok()) << drawing.status().message();
    auto result = replay(drawing->paths, drawing->pixels_per_unit);
    ASSERT_TRUE(result.ok()) << result.status().message();
    std::map<std::string, std::set<std::string>> rules;
    std::map<std::string, ShapeKind> kinds;
    for (std::size_t i = 0; i < result->strokes.size(); ++i) {
        for (const Relation& r : result->strokes[i].chosen.relations())
            rules[drawing->ids[i]].insert(r.rule);
        kinds[drawing->ids[i]] = result->strokes[i].chosen.segments[0].kind;
    }
    EXPECT_EQ(kinds["ground"], ShapeKind::Line);
    EXPECT_TRUE(rules["wall-left"].count("perpendicular"));
    EXPECT_TRUE(rules["wall-right"].count("endpoint"));
    EXPECT_TRUE(rules["roof-right"].count("equal-length"));
    EXPECT_EQ(kinds["window"], ShapeKind::Circle);
    EXPECT_EQ(kinds["sun"], ShapeKind::Circle);
    EXPECT_TRUE(rules["bird-2"].count("identity"));
    EXPECT_TRUE(rules["bird-2"].count("transform"));
    EXPECT_TRUE(rules["bird-3"].count("step"));
    EXPECT_TRUE(rules["bird-mirror"].count("reflection"));
    EXPECT_TRUE(rules["hill-2"].count("identity"));
    // The second and third birds are exactly one step apart, horizontally.
    const Path& b1 = result->strokes[8].chosen.path;
    const Path& b2 = result->strokes[9].chosen.path;
    const Path& b3 = result->strokes[10].chosen.path;
    EXPECT_NEAR((b2.start() - b1.start()).y, 0.0, 1e-9);
    EXPECT_NEAR(distance(b3.start() - b2.start(), b2.start() - b1.start()), 0.0, 1e-9);
}

}  // namespace
}  // namespace exemplar::sketch
