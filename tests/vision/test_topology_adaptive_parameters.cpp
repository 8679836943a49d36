#include "dnurbs/vision/topology_adaptive_parameters.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "../common/error_message.h"

namespace dnurbs {
namespace {

using testing::error_message;

TEST(InflationSwitch, BinarySignOrClampedRamp) {
  EXPECT_EQ(inflation_switch(0.5, 0.5, 0.0), 1.0);  // I >= T inflates
  EXPECT_EQ(inflation_switch(0.49, 0.5, 0.0), -1.0);
  EXPECT_DOUBLE_EQ(inflation_switch(0.6, 0.5, 0.2), 0.5);
  EXPECT_DOUBLE_EQ(inflation_switch(0.4, 0.5, 0.2), -0.5);
  EXPECT_EQ(inflation_switch(0.9, 0.5, 0.2), 1.0);
  EXPECT_EQ(inflation_switch(0.0, 0.5, 0.2), -1.0);
}

TEST(TopologyAdaptiveParameters, ValidationNamesModelParameterAndValue) {
  TopologyAdaptiveParameters parameters;
  EXPECT_NO_THROW(parameters.validate("T-snake", 4.0, 16.0));
  parameters.damping = 0.0;
  EXPECT_NE(error_message([&] {
              parameters.validate("T-snake", 4.0, 16.0);
            }).find("T-snake damping = 0 is not > 0"),
            std::string::npos);
  parameters = TopologyAdaptiveParameters{};
  parameters.threshold = INFINITY;
  EXPECT_NE(error_message([&] {
              parameters.validate("T-surface", 2.0, 4.0);
            }).find("T-surface threshold = inf"),
            std::string::npos);
  parameters = TopologyAdaptiveParameters{};
  parameters.steps_per_reparameterization = 0;
  EXPECT_NE(error_message([&] {
              parameters.validate("T-snake", 4.0, 16.0);
            }).find("steps_per_reparameterization = 0"),
            std::string::npos);
  parameters = TopologyAdaptiveParameters{};
  parameters.rigidity = 0.3;  // 0.2 (4 * 0.05 + 16 * 0.3) = 1.0
  EXPECT_NE(
      error_message([&] { parameters.validate("T-snake", 4.0, 16.0); }).find("= 1, must be < 1"),
      std::string::npos);
  parameters.rigidity = 0.29;
  EXPECT_NO_THROW(parameters.validate("T-snake", 4.0, 16.0));
}

}  // namespace
}  // namespace dnurbs
