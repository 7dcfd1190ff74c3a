// The protocol's value lists are made from the enums' name lists.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "firmware/can/protocol_messages.hpp"
#include "firmware/can/value_list.hpp"

namespace tnv::fw::can {
namespace {

constexpr const char* kTwelveNames[] = {"a", "b", "c", "d", "e", "f", "g", "h", "i", "j", "k", "long_name"};
constexpr const char* kOneName[] = {"only"};

TEST(ValueList, NumbersEachNameByItsPositionPastOneDigit) {
  EXPECT_EQ(std::string(kValueList<kTwelveNames>), "0=a 1=b 2=c 3=d 4=e 5=f 6=g 7=h 8=i 9=j 10=k 11=long_name");
  EXPECT_EQ(std::string(kValueList<kOneName>), "0=only");
}

TEST(ValueList, TheProtocolsEnumListsComeFromTheEnums) {
  // The last value of each enum is the last entry of its list: a value
  // added to an enum is in the documents with its name.
  const auto last_entry = [](const std::string& list) { return list.substr(list.rfind(' ') + 1); };
  const auto entry = [](std::size_t value, const char* name) {
    std::ostringstream out;
    out << value << '=' << name;
    return out.str();
  };
  const std::size_t last_fault = std::size(kFaultReasonNames) - 1;
  EXPECT_EQ(last_entry(detail::kFaultValues), entry(last_fault, to_string(static_cast<FaultReason>(last_fault))));
  const std::size_t last_error = kErrorCodeCount - 1u;
  EXPECT_EQ(last_entry(detail::kErrorValues), entry(last_error, to_string(static_cast<ErrorCode>(last_error))));
  EXPECT_EQ(std::string(detail::kStateValues), "0=disabled 1=dwell 2=moving 3=holding 4=faulted");
  EXPECT_STREQ(to_string(static_cast<FaultReason>(std::size(kFaultReasonNames))), "?");
  EXPECT_STREQ(to_string(static_cast<ErrorCode>(kErrorCodeCount)), "?");
}

}  // namespace
}  // namespace tnv::fw::can
