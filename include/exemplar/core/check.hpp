#pragma once
/// \file
/// Invariant checks that print both operands. A failed check is a bug, not bad input: it aborts
/// with file, line and values. `EXEMPLAR_DCHECK*` compile away in release builds (use them in hot
/// loops).

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

namespace exemplar::detail {
[[noreturn]] void check_failed(const char* file, int line, const std::string& what);

template <typename A, typename B>
std::string format_check(const char* expr_a, const char* op, const char* expr_b, const A& a,
                         const B& b) {
    std::ostringstream out;
    out << expr_a << ' ' << op << ' ' << expr_b << " (" << a << " vs " << b << ')';
    return out.str();
}
}  // namespace exemplar::detail

#define EXEMPLAR_CHECK(cond)                                                      \
    do {                                                                          \
        if (!(cond)) ::exemplar::detail::check_failed(__FILE__, __LINE__, #cond); \
    } while (false)

#define EXEMPLAR_CHECK_OP(a, op, b)                                                       \
    do {                                                                                  \
        const auto& exemplar_a_ = (a);                                                    \
        const auto& exemplar_b_ = (b);                                                    \
        if (!(exemplar_a_ op exemplar_b_))                                                \
            ::exemplar::detail::check_failed(                                             \
                __FILE__, __LINE__,                                                       \
                ::exemplar::detail::format_check(#a, #op, #b, exemplar_a_, exemplar_b_)); \
    } while (false)

#define EXEMPLAR_CHECK_EQ(a, b) EXEMPLAR_CHECK_OP(a, ==, b)
#define EXEMPLAR_CHECK_LT(a, b) EXEMPLAR_CHECK_OP(a, <, b)
#define EXEMPLAR_CHECK_LE(a, b) EXEMPLAR_CHECK_OP(a, <=, b)
#define EXEMPLAR_CHECK_GE(a, b) EXEMPLAR_CHECK_OP(a, >=, b)

#ifdef NDEBUG
#define EXEMPLAR_DCHECK(cond) ((void)0)
#define EXEMPLAR_DCHECK_LT(a, b) ((void)0)
#else
#define EXEMPLAR_DCHECK(cond) EXEMPLAR_CHECK(cond)
#define EXEMPLAR_DCHECK_LT(a, b) EXEMPLAR_CHECK_LT(a, b)
#endif
