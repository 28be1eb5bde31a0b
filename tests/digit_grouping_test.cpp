// model/digit_grouping.h against the standard library's own grouping: an ostream imbued with a
// locale whose numpunct groups by three with ',' (an independent implementation of the rule).
#include "model/digit_grouping.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <locale>
#include <sstream>
#include <string>
#include <vector>

namespace shadesim {
namespace {

struct GroupsOfThree : std::numpunct<char> {
  char do_thousands_sep() const override { return ','; }
  std::string do_grouping() const override { return "\3"; }
};

template <typename Int>
std::string by_locale(Int v) {
  std::ostringstream os;
  os.imbue(std::locale(std::locale::classic(), new GroupsOfThree));
  os << v;
  return os.str();
}

TEST(DigitGrouping, EveryValueUpToAMillionAndItsNegativeAsTheLocaleGroupsThem) {
  for (int64_t v = 0; v <= 1'000'000; ++v) {
    ASSERT_EQ(grouped(v), by_locale(v)) << v;
    ASSERT_EQ(grouped(-v), by_locale(-v)) << -v;
  }
}

TEST(DigitGrouping, TheExtremesOfEachWidthAndEveryPowerOfTenAroundIt) {
  EXPECT_EQ(grouped(std::numeric_limits<int64_t>::min()),
            by_locale(std::numeric_limits<int64_t>::min()));
  EXPECT_EQ(grouped(std::numeric_limits<int64_t>::max()),
            by_locale(std::numeric_limits<int64_t>::max()));
  EXPECT_EQ(grouped(std::numeric_limits<uint64_t>::max()),
            by_locale(std::numeric_limits<uint64_t>::max()));
  EXPECT_EQ(grouped(std::numeric_limits<int32_t>::min()),
            by_locale(std::numeric_limits<int32_t>::min()));
  EXPECT_EQ(grouped(std::numeric_limits<int8_t>::min()),
            by_locale(static_cast<int>(std::numeric_limits<int8_t>::min())));
  uint64_t p = 1;
  for (int k = 0; k < 19; ++k, p *= 10) {
    for (uint64_t v : {p - 1, p, p + 1}) EXPECT_EQ(grouped(v), by_locale(v)) << v;
  }
  EXPECT_EQ(grouped(12345678u), "12,345,678");  // the header's own example, by hand
}

}  // namespace
}  // namespace shadesim
