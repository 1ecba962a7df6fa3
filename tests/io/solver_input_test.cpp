// The top-level "solver": bad values are refused naming the field by its JSON pointer.
#include <gtest/gtest.h>

#include "support/errors.hpp"
#include "support/models.hpp"

namespace solver_input_test {

using namespace beamfea;
using nlohmann::json;

namespace {
json with_solver(const json& solver) {
  json doc = test::linear_cantilever(100.0);
  doc["solver"] = solver;
  return doc;
}
// The message of the InputError that reading `doc` raises ("" if none).
std::string error_message(const json& doc) {
  const auto e = test::thrown<InputError>([&] { load_and_check(doc); });
  return e ? e->what() : "";
}
}  // namespace

TEST(SolverInput, ReadsTheChoice) {
  const Model m = load_and_check(with_solver({{"type", "iterative"}, {"rtol", 1e-8}, {"preconditioner", "hypre"},
                                              {"max_iterations", 50}}));
  EXPECT_EQ(m.solver.type, SolverChoice::Type::Iterative);
  EXPECT_EQ(m.solver.rtol, 1e-8);
  EXPECT_EQ(m.solver.preconditioner, SolverChoice::Preconditioner::Hypre);
  EXPECT_EQ(m.solver.max_iterations, 50);
  EXPECT_TRUE(m.solver.given);
}

TEST(SolverInput, AnUnknownTypeIsRefusedByItsPointerWithTheKnownOnes) {
  const json doc = with_solver({{"type", "multigrid"}});
  EXPECT_EQ(test::input_error_pointer(doc), "/solver/type");
  EXPECT_NE(error_message(doc).find("expected direct, iterative or auto"), std::string::npos) << error_message(doc);
}

TEST(SolverInput, AnRtolOutOfRangeIsRefusedByItsPointer) {
  for (const double rtol : {0.0, -1e-8, 1e-20, 0.5}) {
    const json doc = with_solver({{"rtol", rtol}});
    EXPECT_EQ(test::input_error_pointer(doc), "/solver/rtol") << rtol;
  }
  EXPECT_NE(error_message(with_solver({{"rtol", 0.5}})).find("[1e-15, 0.1]"), std::string::npos);
}

TEST(SolverInput, UnknownKeysAndBadCountsAreRefusedByTheirPointers) {
  EXPECT_EQ(test::input_error_pointer(with_solver({{"rtoll", 1e-8}})), "/solver/rtoll");
  EXPECT_NE(error_message(with_solver({{"rtoll", 1e-8}})).find("rtol"), std::string::npos);
  EXPECT_EQ(test::input_error_pointer(with_solver({{"max_iterations", 0}})), "/solver/max_iterations");
  EXPECT_EQ(test::input_error_pointer(with_solver({{"preconditioner", "ilu"}})), "/solver/preconditioner");
}

}  // namespace solver_input_test
