#include "exemplar/core/image.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace exemplar {
namespace {

TEST(Image, InterleavedLayout) {
    Image im(3, 2, 4);
    im.at(2, 1, 3) = 7.0f;
    EXPECT_EQ(im.data()[(1 * 3 + 2) * 4 + 3], 7.0f);
    EXPECT_EQ(im.pixel(2, 1)[3], 7.0f);
    EXPECT_EQ(im.channel_names(), (std::vector<std::string>{"R", "G", "B", "A"}));
    EXPECT_EQ(im.view().row_stride, 12u);
    EXPECT_EQ(im.view().pixel(2, 1)[3], 7.0f);
}

TEST(Image, ExtractAndConcatRoundTrip) {
    Image a(4, 3, 3);
    Image b(4, 3, 1);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x) {
            for (int c = 0; c < 3; ++c) a.at(x, y, c) = static_cast<float>(x + 10 * y + 100 * c);
            b.at(x, y, 0) = -static_cast<float>(x * y);
        }
    b.set_channel_names({"mask"});
    Image ab = concat_channels({&a, &b});
    ASSERT_EQ(ab.channels(), 4);
    EXPECT_EQ(ab.channel_names()[3], "mask");
    EXPECT_EQ(find_channel(ab, "mask"), 3);
    EXPECT_EQ(find_channel(ab, "nope"), -1);
    Image a2 = extract_channels(ab, 0, 3);
    Image b2 = extract_channels(ab, 3, 1);
    EXPECT_TRUE(std::equal(a.data().begin(), a.data().end(), a2.data().begin()));
    EXPECT_TRUE(std::equal(b.data().begin(), b.data().end(), b2.data().begin()));
}

TEST(Image, SelectChannelsKeepsTheListedOnesInOrder) {
    Image im(3, 2, 4);
    for (std::size_t i = 0; i < im.data().size(); ++i) im.data()[i] = static_cast<float>(i);
    im.set_channel_names({"R", "G", "B", "A"});
    const std::vector<int> picked{3, 1};
    const Image s = select_channels(im, picked);
    ASSERT_EQ(s.channels(), 2);
    EXPECT_EQ(s.channel_names(), (std::vector<std::string>{"A", "G"}));
    for (int y = 0; y < 2; ++y) {
        for (int x = 0; x < 3; ++x) {
            EXPECT_EQ(s.at(x, y, 0), im.at(x, y, 3));
            EXPECT_EQ(s.at(x, y, 1), im.at(x, y, 1));
        }
    }
    const std::vector<int> all{0, 1, 2, 3};
    const Image same = select_channels(im, all);
    EXPECT_TRUE(std::equal(im.data().begin(), im.data().end(), same.data().begin()));
    EXPECT_EQ(same.channel_names(), im.channel_names());
}

TEST(Image, AllFinite) {
    Image im(2, 2, 1, 0.5f);
    EXPECT_TRUE(all_finite(im));
    im.at(1, 1, 0) = std::numeric_limits<float>::quiet_NaN();
    EXPECT_FALSE(all_finite(im));
    im.at(1, 1, 0) = std::numeric_limits<float>::infinity();
    EXPECT_FALSE(all_finite(im));
}

}  // namespace
}  // namespace exemplar
