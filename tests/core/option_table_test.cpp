// The shared range check and field access of the modules' option tables.
#include "exemplar/core/option_table.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string_view>
#include <variant>

namespace exemplar {
namespace {

struct Options {
    int patch_size = 5;
    float weight = 0.5f;
    std::uint64_t seed = 1;
};

struct Spec {
    std::string_view name;
    double min = 0.0, max = 0.0;
    std::variant<int Options::*, float Options::*, std::uint64_t Options::*> field;
};

TEST(OptionTable, ChecksRangeIntegersAndOddValuesWithOneMessage) {
    EXPECT_TRUE(check_option_value("weight", 0.25, 0, 1, false).is_ok());
    EXPECT_EQ(check_option_value("noise", -1, 0, 256, false).message(),
              "noise: -1 is invalid (must be 0..256)");
    EXPECT_EQ(check_option_value("levels", 2.5, 1, 6, true).message(),
              "levels: 2.5 is invalid (must be an integer, 1..6)");
    EXPECT_EQ(check_option_value("patch-size", 4, 3, 31, true, true).message(),
              "patch-size: 4 is invalid (must be odd, 3..31)");
    EXPECT_FALSE(check_option_value("weight", std::nan(""), 0, 1, false).is_ok());
    EXPECT_EQ(format_option_number(0.95), "0.95");
    EXPECT_EQ(format_option_number(12), "12");
}

TEST(OptionTable, ReadsAndSetsFieldsOfAnyType) {
    const Spec patch{"patch-size", 3, 15, &Options::patch_size};
    const Spec weight{"weight", 0, 1, &Options::weight};
    const Spec seed{"seed", 0, 1e9, &Options::seed};
    Options options;
    EXPECT_TRUE(is_integral_option<Options>(patch));
    EXPECT_FALSE(is_integral_option<Options>(weight));
    EXPECT_EQ(get_table_option(options, weight), 0.5);
    ASSERT_TRUE(set_table_option(options, patch, 7, true).is_ok());
    ASSERT_TRUE(set_table_option(options, seed, 42).is_ok());
    EXPECT_EQ(options.patch_size, 7);
    EXPECT_EQ(options.seed, 42u);
    EXPECT_FALSE(set_table_option(options, patch, 8, true).is_ok());
    EXPECT_FALSE(set_table_option(options, weight, 2).is_ok());
    EXPECT_EQ(options.patch_size, 7);
    EXPECT_EQ(options.weight, 0.5f);
}

}  // namespace
}  // namespace exemplar
