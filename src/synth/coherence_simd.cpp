// Highway kernel of add_coherence_row; compiled once per SIMD target, dispatched at run time.
// Compiled without floating-point contraction (CMakeLists.txt): each term is a product rounded
// before it is added, as in the scalar loop.
#include <algorithm>
#include <cstring>

#include "coherence.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "coherence_simd.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace exemplar::synth {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Lanes of doubles (the sums) beside as many int32 lanes (coordinates): N pixels per step, their
// matches read as four interleaved int32 (x, y, angle, error). The last step of a row, shorter
// than N, goes through padded copies.
void AddCoherenceRow(const CoherenceRow& f, int y, double* agree) {
    const hn::ScalableTag<double> d;
    const hn::Rebind<std::int32_t, decltype(d)> di;
    const hn::Rebind<std::uint8_t, decltype(d)> d8;
    const hn::RebindToSigned<decltype(d)> di64;
    constexpr std::size_t kMaxLanes = HWY_MAX_BYTES / sizeof(double);
    const int n = static_cast<int>(hn::Lanes(d));
    const int w = f.width, r = f.radius, P = 2 * r + 1;
    const auto lo = hn::Set(di, -f.reach - 1);
    const auto hi = hn::Set(di, f.reach + 1);
    const auto minus_one = hn::Set(di, -1);
    const auto zero8 = hn::Zero(di);
    const Match* prow = f.matches + static_cast<std::size_t>(y) * w;
    const std::uint8_t* pact =
        f.active != nullptr ? f.active + static_cast<std::size_t>(y) * w : nullptr;
    // Whether the lanes' entries vote: active (or no mask) and matched.
    auto votes = [&](hn::Vec<decltype(di)> mx, const std::uint8_t* act) {
        auto m = hn::Gt(mx, minus_one);
        if (act != nullptr) {
            m = hn::And(m, hn::Ne(hn::PromoteTo(di, hn::LoadU(d8, act)), zero8));
        }
        return hn::MaskFromVec(hn::BitCast(d, hn::PromoteTo(di64, hn::VecFromMask(di, m))));
    };
    for (int dy = -r; dy <= r; ++dy) {
        const int qy = y + dy;
        if (qy < 0 || qy >= f.height) continue;
        const Match* qrow = f.matches + static_cast<std::size_t>(qy) * w;
        const std::uint8_t* qact =
            f.active != nullptr ? f.active + static_cast<std::size_t>(qy) * w : nullptr;
        for (int dx = -r; dx <= r; ++dx) {
            const double* fx =
                f.table + static_cast<std::size_t>((dy + r) * P + dx + r) * f.table_row;
            const double* fy =
                f.table + static_cast<std::size_t>((r - dx) * P + dy + r) * f.table_row;
            // Lanes [x, x + n) with p = (x, y) and q = (x + dx, qy).
            auto step = [&](const Match* p, const std::uint8_t* pa, const Match* q,
                            const std::uint8_t* qa, double* sums) {
                hn::Vec<decltype(di)> px, py, pang, perr, qx, qy_, qang, qerr;
                hn::LoadInterleaved4(di, reinterpret_cast<const std::int32_t*>(p), px, py, pang,
                                     perr);
                hn::LoadInterleaved4(di, reinterpret_cast<const std::int32_t*>(q), qx, qy_, qang,
                                     qerr);
                const auto both = hn::And(votes(px, pa), votes(qx, qa));
                const auto ix = hn::Add(hn::Min(hn::Max(hn::Sub(px, qx), lo), hi), hi);
                const auto iy = hn::Add(hn::Min(hn::Max(hn::Sub(py, qy_), lo), hi), hi);
                const auto term = hn::Mul(hn::GatherIndex(d, fx, hn::PromoteTo(di64, ix)),
                                          hn::GatherIndex(d, fy, hn::PromoteTo(di64, iy)));
                hn::StoreU(hn::Add(hn::LoadU(d, sums), hn::IfThenElseZero(both, term)), d, sums);
            };
            const int x_begin = std::max(0, -dx), x_end = std::min(w, w - dx);
            int x = x_begin;
            for (; x + n <= x_end; x += n) {
                step(prow + x, pact != nullptr ? pact + x : nullptr, qrow + x + dx,
                     qact != nullptr ? qact + x + dx : nullptr, agree + x);
            }
            if (x < x_end) {
                // The row's last lanes, padded with entries that do not vote.
                const auto count = static_cast<std::size_t>(x_end - x);
                Match p[kMaxLanes], q[kMaxLanes];
                std::uint8_t pa[kMaxLanes], qa[kMaxLanes];
                double sums[kMaxLanes];
                std::fill_n(p, n, Match{-1, -1, 0.0f, 0.0f});
                std::fill_n(q, n, Match{-1, -1, 0.0f, 0.0f});
                std::fill_n(pa, n, std::uint8_t{0});
                std::fill_n(qa, n, std::uint8_t{0});
                std::fill_n(sums, n, 0.0);
                std::copy_n(prow + x, count, p);
                std::copy_n(qrow + x + dx, count, q);
                if (pact != nullptr) std::copy_n(pact + x, count, pa);
                if (qact != nullptr) std::copy_n(qact + x + dx, count, qa);
                std::copy_n(agree + x, count, sums);
                step(p, pact != nullptr ? pa : nullptr, q, qact != nullptr ? qa : nullptr, sums);
                std::copy_n(sums, count, agree + x);
            }
        }
    }
}

}  // namespace HWY_NAMESPACE
}  // namespace exemplar::synth
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace exemplar::synth {

HWY_EXPORT(AddCoherenceRow);

void add_coherence_row(const CoherenceRow& field, int y, double* agree) {
    HWY_DYNAMIC_DISPATCH(AddCoherenceRow)(field, y, agree);
}

}  // namespace exemplar::synth
#endif  // HWY_ONCE
