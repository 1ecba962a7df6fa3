#pragma once
// Poses: moving a model from its reference geometry to given joint coordinates or node targets by
// exact rigid-body kinematics (docs/poses.md).
//
// Bodies. Nodes joined by elements (beams and rigid links alike: a pose strains nothing) and by
// ties of all six DOFs form rigid bodies; joints join bodies. A body holding a node whose support
// fixes all six DOFs is ground; a group of bodies joined by joints with no ground keeps the body
// of its first supported node (else of its first node) in place. A spanning tree of the joints
// from those roots (breadth first) gives forward kinematics; each joint outside the tree closes a
// loop.
//
// Joint kinematics, the same as the path solver's (solvers/nonlinear_structure.hpp): a joint from
// body A (the body of nodes[0]) to body B, both at the joint's reference point X,
//   R_B = R_A P(q),  x_B(X) = x_A(X) + R_A d(q),
//   d(q) = sum_{t < translations} q_t a_t,
//   P(q) = exp(q_k a_k) exp(q_k+1 a_k+1) ...  over the rotations, in order (a universal joint's
//          second axis carried by the cross, a virtual spring's Rx Ry Rz),
//   P(q) = exp(sum_k q_k a_k)  for a spherical joint (its coordinates: a rotation vector in its axes).
// A body's pose is (R, t): x = R X + t for the reference position X of any of its points.
//
// Equations (the residual r): each loop joint, r = [x_A(X) + R_A d(q) - x_B(X); log(R_A P R_B^T)]
// (six rows); each node target, r = [x_n - x_target; log(R_n R_target^T) when a rotation is given].
// Unknowns: the joint coordinates that are not given and that some equation depends on (their
// joint lies on a loop or on the path from a root to a target's node): passive coordinates
// (stiffness 0) always, actuator coordinates (stiffness > 0) only when there are node targets.
// A virtual spring's coordinates are link elasticity, not actuators: held at zero unless given.
// Coordinates not given and not unknowns stay at zero (the reference value).
//
// Method: continuation in lambda from the reference (lambda = 0) to the pose (lambda = 1), with
// given coordinates lambda q and node targets moved along the straight line (rotation: exp(lambda
// log R)); at each step Newton's method on the unknowns with the spatial Jacobian (each coordinate
// a twist) and a least-squares step (the loop equations of a planar mechanism are redundant in
// space), steps halved where Newton fails. The Jacobian's decomposition is kept while the residual
// at least halves per iteration (a chord method); steps short of the pose converge to a looser
// tolerance (1e-5), the last one to `tolerance`. Every step's solution is the continuation of the
// one before, so the assembly branch (elbow up or down, working mode) is the reference's.
#include <string>
#include <vector>

#include "core/model.hpp"

namespace beamfea {

struct PoseOptions {
  double max_step_angle = 0.1;    // largest change of a coordinate or target rotation per step (rad)
  double max_step_length = 0.05;  // largest target move per step, times the model's length scale
  int max_newton_iterations = 25;
  int max_halvings = 12;           // of a step where Newton fails, before the pose is unreachable
  double tolerance = 1e-11;        // residual, positions over the length scale
  double rank_tolerance = 1e-9;    // singular value over the largest: below, a direction is lost
  void validate() const;
};

// The posed geometry: every joint's coordinates and every body's rigid motion.
struct PoseSolution {
  std::vector<Eigen::VectorXd> q;  // per joint, measured from the reference
  std::vector<int> body_of_node;
  std::vector<Mat3> R;             // per body
  std::vector<Vec3> t;             // per body: x = R X + t
  int steps = 0;                   // continuation steps taken
  int newton_iterations = 0;       // in all steps
  int jacobians = 0;               // Jacobians made and decomposed, in all steps
};

// Solves `pose` on `model` (its reference geometry). Throws ModelError naming the joint or node at
// fault: a target beyond reach or a loop that cannot close (Newton fails even in small steps), a
// pose where the unknown coordinates are not determined (rank loss: a singular pose, or too few
// targets), a coordinate outside its joint's limits.
PoseSolution solve_pose(const Model& model, const Pose& pose, const PoseOptions& options = {});

// Moves the model to the solved pose: node positions, element and member orientation vectors and
// rigid arms, joint axes (each coordinate's axis where the pose carries it), support frames (a
// support on a body that turns becomes skewed with the body), point masses' inertia; loads in
// global axes, prescribed values, ties and linear constraints stay as given. Joint coordinates are
// zero again at the posed geometry, which becomes the reference of every analysis.
void apply_pose(Model& model, const PoseSolution& solution);

// Both, with model.pose; fills model.pose.solved. Nothing when no pose is given.
void pose_model(Model& model, const PoseOptions& options = {});

}  // namespace beamfea
