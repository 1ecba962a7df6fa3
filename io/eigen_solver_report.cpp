#include "io/eigen_solver_report.hpp"

namespace beamfea {

ojson eigen_solver_json(const EigenSolverReport& report) {
  ojson o = ojson::object();
  o["type"] = report.iterative ? "iterative" : "direct";
  o["iterations"] = report.iterations;
  if (report.iterative) o["linear_iterations"] = report.linear_iterations;
  o["residual"] = report.residual;
  return o;
}

}  // namespace beamfea
