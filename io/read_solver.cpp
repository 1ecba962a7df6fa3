// Model reader, part 6: the top-level "solver" (core/model.hpp, SolverChoice; docs/analyses/solver.md):
//   "solver": {"type": "direct" | "iterative" | "auto", "rtol": 1e-10,
//              "preconditioner": "gamg" | "hypre", "max_iterations": n}
#include "core/errors.hpp"
#include "io/json_util.hpp"
#include "io/model_reader_parts.hpp"

namespace beamfea::reader {

using namespace json_in;

namespace {

// The documented bounds of "rtol": below 1e-15 no double-precision residual can be trusted to
// reach it; 1 or more accepts any answer.
constexpr double kMinRtol = 1e-15;
constexpr double kMaxRtol = 0.1;
constexpr int kMaxIterations = 100'000'000;

}  // namespace

void read_solver(ReadState& s) {
  const json* d = field(s.doc, "solver");
  if (!d) return;
  const Pointer p("/solver");
  const Fields f(object(*d, p, "solver"), p, {"type", "rtol", "preconditioner", "max_iterations"});
  SolverChoice& choice = s.model.solver;
  choice.given = true;
  if (const json* t = f.get("type")) {
    const std::string type = string(*t, child(p, "type"), "solver type");
    if (type == "direct") choice.type = SolverChoice::Type::Direct;
    else if (type == "iterative") choice.type = SolverChoice::Type::Iterative;
    else if (type == "auto") choice.type = SolverChoice::Type::Auto;
    else throw InputError(child(p, "type"), "solver: unknown type '" + type + "' (expected direct, iterative or auto)");
  }
  if (const json* r = f.get("rtol")) {
    const Pointer rp = child(p, "rtol");
    choice.rtol = positive(*r, rp, "solver rtol");
    if (choice.rtol < kMinRtol || choice.rtol > kMaxRtol)
      throw InputError(rp, "solver rtol must lie in [1e-15, 0.1]");
  }
  if (const json* pc = f.get("preconditioner")) {
    const std::string name = string(*pc, child(p, "preconditioner"), "solver preconditioner");
    if (name == "gamg") choice.preconditioner = SolverChoice::Preconditioner::Gamg;
    else if (name == "hypre") choice.preconditioner = SolverChoice::Preconditioner::Hypre;
    else throw InputError(child(p, "preconditioner"), "solver: unknown preconditioner '" + name + "' (expected gamg or hypre)");
  }
  if (const json* n = f.get("max_iterations"))
    choice.max_iterations = integer_in(*n, child(p, "max_iterations"), "solver max_iterations", 1, kMaxIterations);
}

}  // namespace beamfea::reader
