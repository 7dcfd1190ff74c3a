// The one expansion of a listed enum (hal/listed_enum.hpp): values in list
// order, names by value, the count, the values' array and the fallback name.
#include "hal/listed_enum.hpp"

#include <gtest/gtest.h>

#include <string_view>

namespace {

#define TNV_TEST_COLOURS(X) \
  X(red)                    \
  X(green, 7) /* a further column is ignored by the expansion */ \
  X(blue)

TNV_LISTED_ENUM(Colour, TNV_TEST_COLOURS)

static_assert(static_cast<int>(Colour::red) == 0 && static_cast<int>(Colour::blue) == 2);
static_assert(kColourCount == 3);

TEST(ListedEnum, NamesValuesAndCountFollowTheList) {
  ASSERT_EQ(kColourNames.size(), 3u);
  EXPECT_EQ(std::string_view(kColourNames[1]), "green");
  ASSERT_EQ(kColours.size(), 3u);
  for (std::size_t i = 0; i < kColours.size(); ++i) {
    EXPECT_EQ(static_cast<std::size_t>(kColours[i]), i);
    EXPECT_EQ(std::string_view(to_string(kColours[i])), kColourNames[i]);
  }
}

TEST(ListedEnum, AValueOutsideTheListHasNoName) {
  EXPECT_EQ(std::string_view(to_string(static_cast<Colour>(3))), "?");
  EXPECT_EQ(std::string_view(to_string(static_cast<Colour>(255))), "?");
}

}  // namespace
