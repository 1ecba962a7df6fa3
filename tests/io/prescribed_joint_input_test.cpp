// A prescribed joint coordinate is read and checked like every other field: a joint and its
// coordinate or a node and its DOF (never a mix), a coordinate the joint has, a finite value, and
// the coordinate it reaches (from the pose, or from the reference geometry) within the joint's
// limits. Each error names the entry's field by its JSON pointer.
#include <gtest/gtest.h>

#include <limits>
#include <nlohmann/json.hpp>

#include "support/errors.hpp"
#include "support/models.hpp"

namespace prescribed_joint_input_test {

using nlohmann::json;
using beamfea::test::input_error_pointer;

// Beam A-B clamped at A, a prismatic slider B-C along x (one coordinate, limits [-0.01, 0.02]),
// beam C-D.
json slider() {
  json doc = beamfea::test::cantilever(1.0, 2.1e11, 8.0e10, 1e-3, 2e-6, 3e-6, 4e-6);
  doc["nodes"].push_back({{"id", "C"}, {"xyz", {1.0, 0, 0}}});
  doc["nodes"].push_back({{"id", "D"}, {"xyz", {2.0, 0, 0}}});
  doc["elements"].push_back({{"id", "e2"}, {"type", "beam"}, {"nodes", {"C", "D"}}, {"material", "m"}, {"section", "s"},
                             {"orientation", {0, 0, 1}}});
  doc["joints"] = json::array({{{"id", "slide"}, {"type", "prismatic"}, {"nodes", {"B", "C"}}, {"axes", {{1, 0, 0}}},
                                {"stiffness", {1e5}}, {"limits", {{-0.01, 0.02}}}}});
  doc["analyses"] = json::array({{{"id", "lin"}, {"type", "linear_static"}}});
  return doc;
}

json with_prescribed(const json& entry, json doc = slider()) {
  doc["prescribed"] = json::array({entry});
  return doc;
}

TEST(PrescribedJointInput, AGoodEntryPasses) {
  EXPECT_EQ(input_error_pointer(with_prescribed({{"joint", "slide"}, {"coordinate", 0}, {"value", 0.015}})), "(no error)");
  EXPECT_EQ(input_error_pointer(with_prescribed({{"joint", "slide"}, {"value", -0.01}})), "(no error)");  // coordinate 0
}

TEST(PrescribedJointInput, WrongJointsCoordinatesAndValuesAreNamedByPointer) {
  const auto at = [](const json& entry) { return input_error_pointer(with_prescribed(entry)); };
  EXPECT_EQ(at({{"joint", "nope"}, {"value", 0.0}}), "/prescribed/0/joint");
  EXPECT_EQ(at({{"joint", "slide"}, {"coordinate", 1}, {"value", 0.0}}), "/prescribed/0/coordinate");  // a prismatic has one
  EXPECT_EQ(at({{"joint", "slide"}, {"coordinate", -1}, {"value", 0.0}}), "/prescribed/0/coordinate");
  EXPECT_EQ(at({{"joint", "slide"}, {"coordinate", 0.5}, {"value", 0.0}}), "/prescribed/0/coordinate");
  EXPECT_EQ(at({{"joint", "slide"}, {"coordinate", "0"}, {"value", 0.0}}), "/prescribed/0/coordinate");
  EXPECT_EQ(at({{"joint", "slide"}, {"value", std::numeric_limits<double>::infinity()}}), "/prescribed/0/value");
  EXPECT_EQ(at({{"joint", "slide"}, {"value", 1e300}}), "/prescribed/0/value");
  EXPECT_EQ(at({{"joint", "slide"}, {"value", "0.01"}}), "/prescribed/0/value");
  EXPECT_EQ(at({{"joint", "slide"}}), "/prescribed/0/value");  // missing: the key's pointer
  EXPECT_EQ(at({{"joint", "slide"}, {"cordinate", 0}, {"value", 0.0}}), "/prescribed/0/cordinate");
}

TEST(PrescribedJointInput, AJointAndANodeInOneEntryAreAMix) {
  const auto at = [](const json& entry) { return input_error_pointer(with_prescribed(entry)); };
  EXPECT_EQ(at({{"joint", "slide"}, {"node", "D"}, {"value", 0.0}}), "/prescribed/0/node");
  EXPECT_EQ(at({{"joint", "slide"}, {"dof", "ux"}, {"value", 0.0}}), "/prescribed/0/dof");
  EXPECT_EQ(at({{"node", "D"}, {"dof", "ux"}, {"coordinate", 0}, {"value", 0.0}}), "/prescribed/0/coordinate");
}

// The limits bound the coordinate reached: the value from the reference geometry, or from the
// pose's coordinate when the model is posed (0.015 + 0.01 = 0.025 > 0.02).
TEST(PrescribedJointInput, TheCoordinateReachedMustLieWithinTheJointsLimits) {
  const auto at = [](const json& doc) { return input_error_pointer(doc); };
  EXPECT_EQ(at(with_prescribed({{"joint", "slide"}, {"value", 0.03}})), "/prescribed/0/value");
  EXPECT_EQ(at(with_prescribed({{"joint", "slide"}, {"value", -0.011}})), "/prescribed/0/value");
  json posed = slider();
  posed["pose"] = {{"joints", {{"slide", 0.015}}}};
  EXPECT_EQ(at(with_prescribed({{"joint", "slide"}, {"value", 0.01}}, posed)), "/prescribed/0/value");
  EXPECT_EQ(at(with_prescribed({{"joint", "slide"}, {"value", -0.02}}, posed)), "(no error)");
  const auto e = beamfea::test::thrown<beamfea::InputError>(
      [&] { beamfea::load_and_check(with_prescribed({{"joint", "slide"}, {"value", 0.01}}, posed)); });
  ASSERT_TRUE(e);
  EXPECT_NE(std::string(e->what()).find("slide"), std::string::npos) << e->what();
  EXPECT_NE(std::string(e->what()).find("limits"), std::string::npos) << e->what();
}

}  // namespace prescribed_joint_input_test
