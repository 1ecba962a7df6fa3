// URDF import (io/urdf_reader.hpp): a three-axis arm written here with non-trivial rpy origins and
// inclined axes, converted and analysed, against the robot's kinematics computed here:
//   - the reference (zero joint values) position of every link frame node is the product of the
//     URDF transforms T = Trans(xyz) Rz(yaw) Ry(pitch) Rx(roll) from the root (URDF's convention);
//   - with rigid links and joint springs K (side-car), the tool compliance is J K^-1 J^T, J the
//     6x3 geometric Jacobian (z_i x (p - p_i); z_i) of the zero pose (Pashkevich et al. 2010, eq. 5
//     with the links rigid);
//   - under gravity, the tool sag is J K^-1 tau_g, tau_g,i = sum over the masses carried by joint i
//     of (m g) . (z_i x (c - p_i)), c the mass's centre (the inertials at their centres of mass);
//   - a prismatic joint: the tool compliance of a slider spring k is a a^T / k;
//   - a flexible link (side-car beam) on a revolute spring: the tool's transverse compliance is
//     L^2 / k + L^3 / (3 E I) (a cantilever on a rotational spring);
//   - bad input: a dangling joint, an unknown side-car key or link: exit 2 naming it, nothing written.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <nlohmann/json.hpp>

#include "io/run.hpp"
#include "io/urdf_reader.hpp"
#include "support/files.hpp"
#include "support/models.hpp"

namespace urdf_import_test {

using nlohmann::json;
using Mat3 = Eigen::Matrix3d;
using Vec3 = Eigen::Vector3d;

struct Tf {
  Mat3 R = Mat3::Identity();
  Vec3 p = Vec3::Zero();
  Tf operator*(const Tf& o) const { return {R * o.R, p + R * o.p}; }
};

// URDF's origin: R = Rz(yaw) Ry(pitch) Rx(roll), then the translation xyz.
Tf origin(const Vec3& xyz, const Vec3& rpy) {
  const Mat3 R = (Eigen::AngleAxisd(rpy[2], Vec3::UnitZ()) * Eigen::AngleAxisd(rpy[1], Vec3::UnitY()) *
                  Eigen::AngleAxisd(rpy[0], Vec3::UnitX())).toRotationMatrix();
  return {R, xyz};
}

std::string v3(const Vec3& v) {
  char b[128];
  std::snprintf(b, sizeof b, "%.17g %.17g %.17g", v[0], v[1], v[2]);
  return b;
}

// The arm: base -q1- l1 -q2- l2 -q3- l3 =fixed= tool. Joint origins and axes (in the joint frame):
struct JointSpec {
  const char* name;
  const char* type;
  const char* parent;
  const char* child;
  Vec3 xyz, rpy, axis;
};
const JointSpec kJoints[] = {
    {"q1", "continuous", "base", "l1", {0.0, 0.0, 0.3}, {0.0, 0.0, 0.4}, {0, 0, 1}},
    {"q2", "revolute", "l1", "l2", {0.05, 0.0, 0.2}, {1.2, 0.3, -0.2}, {0, 0, 1}},
    {"q3", "continuous", "l2", "l3", {0.5, 0.1, 0.0}, {0.2, -0.4, 0.7}, {0.6, 0.0, 0.8}},
    {"tool_mount", "fixed", "l3", "tool", {0.4, 0.0, 0.05}, {0.3, 0.1, 0.0}, {1, 0, 0}},
};
// Inertials of l1..l3 (origin xyz, rpy, mass; inertia ixx iyy izz with ixy = 0.01).
struct InertialSpec {
  const char* link;
  Vec3 xyz, rpy;
  double mass;
};
const InertialSpec kInertials[] = {
    {"l1", {0.02, 0.01, 0.1}, {0.1, 0.2, 0.3}, 4.0},
    {"l2", {0.25, 0.05, 0.0}, {0.0, 0.5, 0.0}, 3.0},
    {"l3", {0.2, 0.0, 0.02}, {0.0, 0.0, 0.0}, 1.5},
};

std::string arm_urdf(bool dangling = false) {
  std::string s = "<robot name=\"arm3\">\n  <link name=\"base\"/>\n";
  for (const auto& in : kInertials)
    s += std::string("  <link name=\"") + in.link + "\"><inertial><origin xyz=\"" + v3(in.xyz) + "\" rpy=\"" + v3(in.rpy) +
         "\"/><mass value=\"" + std::to_string(in.mass) +
         "\"/><inertia ixx=\"0.03\" ixy=\"0.01\" ixz=\"0\" iyy=\"0.02\" iyz=\"0\" izz=\"0.04\"/></inertial></link>\n";
  s += "  <link name=\"tool\"/>\n";
  for (const auto& j : kJoints) {
    const std::string child = dangling && std::string(j.name) == "q3" ? "l4" : j.child;
    s += std::string("  <joint name=\"") + j.name + "\" type=\"" + j.type + "\"><parent link=\"" + j.parent + "\"/><child link=\"" +
         child + "\"/><origin xyz=\"" + v3(j.xyz) + "\" rpy=\"" + v3(j.rpy) + "\"/><axis xyz=\"" + v3(j.axis) + "\"/>" +
         (std::string(j.type) == "revolute" ? "<limit lower=\"-2\" upper=\"2\" effort=\"100\" velocity=\"1\"/>" : "") + "</joint>\n";
  }
  return s + "</robot>\n";
}

// Joint limits are emitted for poses; a model reader that does not know the key yet would refuse
// it, so the analyses here run without them where that is so.
json runnable(json doc) {
  json probe = {{"nodes", {{{"id", "a"}, {"xyz", {0, 0, 0}}}, {{"id", "b"}, {"xyz", {0, 0, 0}}}}},
                {"joints", {{{"id", "j"}, {"type", "revolute"}, {"nodes", {"a", "b"}}, {"axes", {{0, 0, 1}}}, {"limits", {{-1, 1}}}}}},
                {"supports", {{{"node", "a"}, {"fix", "all"}}}}};
  bool knows_limits = true;
  try {
    beamfea::load_and_check(probe);
  } catch (const beamfea::InputError&) {
    knows_limits = false;
  }
  if (!knows_limits && doc.contains("joints"))
    for (auto& j : doc["joints"]) j.erase("limits");
  return doc;
}

json convert(const std::string& urdf, const std::optional<json>& sidecar) {
  return json::parse(beamfea::urdf_to_model(urdf, "arm3.urdf", sidecar, "flex.json").dump());
}

beamfea::ojson analyse(json doc, const json& analyses) {
  doc = runnable(std::move(doc));
  doc["analyses"] = analyses;
  const beamfea::Model model = beamfea::load_and_check(doc);
  const beamfea::RunReport report = beamfea::run_document(model, doc, {});
  EXPECT_FALSE(report.failed);
  return report.results["analyses"];
}

const json* node_of(const json& doc, const std::string& id) {
  for (const auto& n : doc["nodes"])
    if (n["id"] == id) return &n;
  return nullptr;
}

// The link frames at the zero pose, and the joints' positions and global axes.
struct Kinematics {
  std::map<std::string, Tf> frame;  // per link
  std::vector<Vec3> p, z;           // per movable joint
};
Kinematics kinematics() {
  Kinematics k;
  k.frame["base"] = Tf{};
  for (const auto& j : kJoints) {
    const Tf J = k.frame[j.parent] * origin(j.xyz, j.rpy);
    k.frame[j.child] = J;
    if (std::string(j.type) != "fixed") {
      k.p.push_back(J.p);
      k.z.push_back(J.R * j.axis.normalized());
    }
  }
  return k;
}

const double kSpring[3] = {2.0e4, 1.5e4, 8.0e3};
const json kSidecar = {{"joints", {{"q1", {{"stiffness", {kSpring[0]}}}}, {"q2", {{"stiffness", {kSpring[1]}}}},
                                   {"q3", {{"stiffness", {kSpring[2]}}}}}}};

TEST(UrdfImport, LinkFramesAreTheProductOfTheUrdfTransforms) {
  const json doc = convert(arm_urdf(), kSidecar);
  const Kinematics k = kinematics();
  for (const char* link : {"base", "l1", "l2", "l3", "tool"}) {
    const json* n = node_of(doc, link);
    ASSERT_NE(n, nullptr) << link;
    for (int i = 0; i < 3; ++i) EXPECT_NEAR((*n)["xyz"][i].get<double>(), k.frame.at(link).p[i], 1e-12) << link << " " << i;
  }
  // Joint ids are the URDF's names; axes in global components; the revolute joint's limits.
  ASSERT_EQ(doc["joints"].size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(doc["joints"][i]["id"], kJoints[i].name);
    EXPECT_EQ(doc["joints"][i]["type"], "revolute");
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(doc["joints"][i]["axes"][0][c].get<double>(), k.z[i][c], 1e-12);
  }
  EXPECT_FALSE(doc["joints"][0].contains("limits"));  // continuous
  EXPECT_EQ(doc["joints"][1]["limits"], json::parse("[[-2.0, 2.0]]"));
  // The root link is supported.
  EXPECT_EQ(doc["supports"], json::parse(R"([{"node": "base", "fix": "all"}])"));
}

TEST(UrdfImport, ToolComplianceOfRigidLinksOnJointSpringsIsJacobianTimesInverseStiffness) {
  json doc = convert(arm_urdf(), kSidecar);
  const beamfea::ojson r = analyse(doc, {{{"id", "k"}, {"type", "stiffness"}, {"node", "tool"}}})["k"];
  ASSERT_EQ(r["status"], "ok") << r.dump();
  const Kinematics k = kinematics();
  const Vec3 pt = k.frame.at("tool").p;
  Eigen::Matrix<double, 6, 3> Jac;
  for (int i = 0; i < 3; ++i) Jac.col(i) << k.z[i].cross(pt - k.p[i]), k.z[i];
  const Vec3 kinv(1 / kSpring[0], 1 / kSpring[1], 1 / kSpring[2]);
  const Eigen::Matrix<double, 6, 6> C = Jac * kinv.asDiagonal() * Jac.transpose();
  const double scale = C.cwiseAbs().maxCoeff();
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) EXPECT_NEAR(r["compliance"][i][j].get<double>(), C(i, j), 1e-9 * scale) << i << "," << j;
}

TEST(UrdfImport, ToolSagUnderGravityIsJacobianTimesInverseStiffnessTimesGravityTorques) {
  json doc = convert(arm_urdf(), kSidecar);
  ASSERT_EQ(doc["masses"].size(), 3u);
  const Vec3 g(0.0, 0.0, -9.81);
  doc["gravity"] = {g[0], g[1], g[2]};
  const beamfea::ojson r = analyse(doc, {{{"id", "lin"}, {"type", "linear_static"}}})["lin"];
  ASSERT_EQ(r["status"], "ok") << r.dump();
  const Kinematics k = kinematics();
  // The masses' centres; joint i carries the links from its child on (l_i+1 ... l3).
  Vec3 tau = Vec3::Zero();
  for (int m = 0; m < 3; ++m) {
    const Tf& F = k.frame.at(kInertials[m].link);
    const Vec3 c = F.p + F.R * kInertials[m].xyz;
    for (int i = 0; i <= m; ++i) tau[i] += (kInertials[m].mass * g).dot(k.z[i].cross(c - k.p[i]));
  }
  const Vec3 q(tau[0] / kSpring[0], tau[1] / kSpring[1], tau[2] / kSpring[2]);
  const Vec3 pt = k.frame.at("tool").p;
  Vec3 u = Vec3::Zero();
  for (int i = 0; i < 3; ++i) u += k.z[i].cross(pt - k.p[i]) * q[i];
  ASSERT_GT(u.norm(), 1e-4);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(r["nodes"]["tool"]["displacement"][c].get<double>(), u[c], 1e-9 * u.norm()) << c;
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(r["joints"][kJoints[i].name]["coordinates"][0].get<double>(), q[i], 1e-9 * q.norm()) << i;
}

TEST(UrdfImport, PrismaticJointBecomesASliderSpring) {
  const Vec3 rpy(0.3, -0.5, 0.9), axis(0.0, 0.6, 0.8);
  const std::string urdf = std::string("<robot name=\"slider\"><link name=\"base\"/><link name=\"carriage\"/><link name=\"tool\"/>") +
                           "<joint name=\"s\" type=\"prismatic\"><parent link=\"base\"/><child link=\"carriage\"/><origin xyz=\"0.1 0.2 0.3\" rpy=\"" +
                           v3(rpy) + "\"/><axis xyz=\"" + v3(axis) + "\"/><limit lower=\"0\" upper=\"0.5\" effort=\"1\" velocity=\"1\"/></joint>" +
                           "<joint name=\"t\" type=\"fixed\"><parent link=\"carriage\"/><child link=\"tool\"/><origin xyz=\"0.2 0 0\"/></joint></robot>";
  const double k = 3.0e3;
  const json doc = convert(urdf, json{{"joints", {{"s", {{"stiffness", {k}}}}}}});
  ASSERT_EQ(doc["joints"].size(), 1u);
  EXPECT_EQ(doc["joints"][0]["type"], "prismatic");
  EXPECT_EQ(doc["joints"][0]["limits"], json::parse("[[0.0, 0.5]]"));
  const beamfea::ojson r = analyse(doc, {{{"id", "k"}, {"type", "stiffness"}, {"node", "tool"}}})["k"];
  ASSERT_EQ(r["status"], "ok") << r.dump();
  const Vec3 a = origin(Vec3::Zero(), rpy).R * axis;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(r["compliance"][i][j].get<double>(), a[i] * a[j] / k, 1e-9 / k) << i << "," << j;
  for (int i = 3; i < 6; ++i) EXPECT_NEAR(r["compliance"][i][i].get<double>(), 0.0, 1e-15);
}

TEST(UrdfImport, FlexibleLinkFromTheSidecarAddsItsCantileverCompliance) {
  // base -q (about the joint frame's z, spring k)- arm, arm flexible from its frame to (L, 0, 0),
  // tool at the arm's end. The joint frame is turned by rpy: the arm lies along R x.
  const double L = 0.8, k = 5.0e3, E = 7.0e10, I = 2.0e-8;
  const Vec3 rpy(0.4, 0.2, -0.6);
  const std::string urdf = std::string("<robot name=\"one\"><link name=\"base\"/><link name=\"arm\"/><link name=\"tool\"/>") +
                           "<joint name=\"q\" type=\"continuous\"><parent link=\"base\"/><child link=\"arm\"/><origin xyz=\"0 0 0.5\" rpy=\"" +
                           v3(rpy) + "\"/><axis xyz=\"0 0 1\"/></joint><joint name=\"t\" type=\"fixed\"><parent link=\"arm\"/>" +
                           "<child link=\"tool\"/><origin xyz=\"" + v3(Vec3(L, 0, 0)) + "\"/></joint></robot>";
  const json sidecar = {{"joints", {{"q", {{"stiffness", {k}}}}}},
                        {"materials", {{{"id", "al"}, {"E", E}, {"G", E / 2.6}}}},
                        {"sections", {{{"id", "tube"}, {"A", 1e-4}, {"Iy", I}, {"Iz", I}, {"J", 2 * I}}}},
                        {"links", {{"arm", {{"beam", {{"material", "al"}, {"section", "tube"}, {"from", {0, 0, 0}}, {"to", {L, 0, 0}},
                                                      {"orientation", {0, 0, 1}}, {"divisions", 4}}}}}}}};
  const json doc = convert(urdf, sidecar);
  const beamfea::ojson r = analyse(doc, {{{"id", "k"}, {"type", "stiffness"}, {"node", "tool"}}})["k"];
  ASSERT_EQ(r["status"], "ok") << r.dump();
  // Along the joint axis z' and across (y' = z' x x'): a cantilever on a rotational spring.
  const Mat3 R = origin(Vec3::Zero(), rpy).R;
  const Vec3 y = R.col(1), z = R.col(2);
  Mat3 C;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) C(i, j) = r["compliance"][i][j].get<double>();
  const double across = L * L / k + L * L * L / (3 * E * I), along = L * L * L / (3 * E * I);
  EXPECT_NEAR(y.dot(C * y), across, 1e-9 * across);
  EXPECT_NEAR(z.dot(C * z), along, 1e-9 * across);
}

TEST(UrdfImport, BadInputExitsTwoNamingTheCulpritAndWritesNothing) {
  const auto dir = beamfea::test::temp_dir("urdf_bad");
  beamfea::test::write_file(dir / "dangling.urdf", arm_urdf(true));
  const auto out = dir / "model.json";
  auto r = beamfea::test::run_cli("urdf " + (dir / "dangling.urdf").string() + " -o " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("q3"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("l4"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out));

  beamfea::test::write_file(dir / "arm.urdf", arm_urdf());
  beamfea::test::write_file(dir / "typo.json", R"({"jionts": {"q1": {"stiffness": [1.0]}}})");
  r = beamfea::test::run_cli("urdf " + (dir / "arm.urdf").string() + " --sidecar " + (dir / "typo.json").string() + " -o " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("/jionts"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("did you mean 'joints'"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out));

  beamfea::test::write_file(dir / "link.json", R"({"links": {"l5": {"beam": {}}}})");
  r = beamfea::test::run_cli("urdf " + (dir / "arm.urdf").string() + " --sidecar " + (dir / "link.json").string() + " -o " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("/links/l5"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("unknown link 'l5'"), std::string::npos) << r.output;

  // A good conversion writes the model, which the program then checks.
  beamfea::test::write_file(dir / "flex.json", kSidecar.dump());
  r = beamfea::test::run_cli("urdf " + (dir / "arm.urdf").string() + " --sidecar " + (dir / "flex.json").string() + " -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json written = beamfea::test::read_json(out);
  EXPECT_EQ(written["joints"].size(), 3u);
  json runnable_model = runnable(written);
  runnable_model["analyses"] = {{{"id", "k"}, {"type", "stiffness"}, {"node", "tool"}}};
  EXPECT_NO_THROW(beamfea::load_and_check(runnable_model));
  std::filesystem::remove_all(dir);
}

}  // namespace urdf_import_test
