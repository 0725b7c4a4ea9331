#pragma once
// Geometry of the alignment marks, shared by the raster sheet (sheet.cpp) and the vector PDF
// (sheet_pdf.cpp).

#include <span>

namespace exemplar::marks {

/// One black ring of a mark (a disc when inner is 0), in units of the mark's radius.
struct Band {
    double outer;
    double inner;
};

// The top-left mark has two black rings and a dot (five nested contours), the others one ring
// and a dot (three). Outermost first.
inline constexpr Band kPlainMark[] = {{1.0, 0.6}, {0.3, 0.0}};
inline constexpr Band kCornerMark[] = {{1.0, 0.8}, {0.6, 0.4}, {0.2, 0.0}};

/// The black bands of the top-left (`corner`) or of another mark.
inline std::span<const Band> bands(bool corner) {
    if (corner) return kCornerMark;
    return kPlainMark;
}

}  // namespace exemplar::marks
