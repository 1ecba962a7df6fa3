#include "solvers/pose.hpp"

#include <fmt/format.h>

#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <numeric>

#include "core/errors.hpp"

namespace beamfea {

void PoseOptions::validate() const {
  if (!(max_step_angle > 0.0) || !(max_step_length > 0.0) || max_newton_iterations < 1 || max_halvings < 0 ||
      !(tolerance > 0.0) || !(rank_tolerance > 0.0))
    throw std::invalid_argument("PoseOptions: steps, iterations and tolerances must be positive");
}

namespace {

// A Newton iterate whose residual grew this many times above the step's first one diverges: the
// step is halved rather than iterated further.
constexpr double kDivergence = 1e3;
// A step that converged grows by this factor (up to the first step's size) for the next one.
constexpr double kStepGrowth = 1.5;
// A Newton update with a kept Jacobian decomposition (a chord step) must shrink the residual at
// least by this factor, else the Jacobian is made anew at the iterate.
constexpr double kChordContraction = 0.5;
// The residual (positions over the length scale, rotations in rad) at which a continuation step
// short of the pose (lambda < 1) has converged: its solution only starts the next step, whose
// secant predictor errs by far more (O(h^2), h ~ 0.1); the last step converges to the options'
// tolerance. Steps stay as small as before, so the branch followed is the same.
constexpr double kStepTolerance = 1e-5;

// The model's bodies and the spanning tree of its joints.
struct Topology {
  int bodies = 0;
  std::vector<int> body_of_node;
  std::vector<int> order;         // bodies, parents before children
  std::vector<int> parent_joint;  // per body: the tree joint to its parent (-1: a root)
  std::vector<char> forward;      // per body: its parent is the body of the joint's nodes[0]
  std::vector<int> parent_body;
  std::vector<int> loops;         // joints outside the tree
  std::vector<int> offset;        // per joint: its first coordinate in the flat vector of all
  int coordinates = 0;
};

int find_root(std::vector<int>& up, int i) {
  while (up[i] != i) i = up[i] = up[up[i]];
  return i;
}

Topology topology_of(const Model& m) {
  const int nn = static_cast<int>(m.nodes.size());
  std::vector<int> up(nn);
  std::iota(up.begin(), up.end(), 0);
  auto join = [&](int a, int b) { up[find_root(up, a)] = find_root(up, b); };
  for (const auto& el : m.elements) join(el.nodes[0], el.nodes[1]);
  for (const auto& tie : m.ties) {
    if (std::find(tie.dofs.begin(), tie.dofs.end(), false) != tie.dofs.end())
      throw ModelError("tie between nodes '" + m.nodes[tie.nodes[0]].id + "' and '" + m.nodes[tie.nodes[1]].id + "'",
                       "a posed model needs ties of all six DOFs (use a joint for a partial connection)");
    join(tie.nodes[0], tie.nodes[1]);
  }
  Topology t;
  t.body_of_node.assign(nn, -1);
  std::vector<int> body_of_root(nn, -1);
  for (int n = 0; n < nn; ++n) {
    int& b = body_of_root[find_root(up, n)];
    if (b < 0) b = t.bodies++;
    t.body_of_node[n] = b;
  }
  t.offset.resize(m.joints.size());
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    t.offset[j] = t.coordinates;
    t.coordinates += m.joints[j].coordinates();
  }
  // Joints at each body, then a breadth-first forest: ground bodies first, then the body of each
  // group's first supported node, then of its first node.
  std::vector<std::vector<int>> at(t.bodies);
  for (std::size_t j = 0; j < m.joints.size(); ++j)
    for (int k = 0; k < 2; ++k) at[t.body_of_node[m.joints[j].nodes[k]]].push_back(static_cast<int>(j));
  t.parent_joint.assign(t.bodies, -1);
  t.parent_body.assign(t.bodies, -1);
  t.forward.assign(t.bodies, 1);
  std::vector<char> seen(t.bodies, 0), tree_joint(m.joints.size(), 0);
  std::deque<int> queue;
  auto grow = [&]() {
    while (!queue.empty()) {
      const int b = queue.front();
      queue.pop_front();
      t.order.push_back(b);
      for (const int j : at[b]) {
        const auto& jt = m.joints[j];
        const int a = t.body_of_node[jt.nodes[0]], c = t.body_of_node[jt.nodes[1]];
        const int other = a == b ? c : a;
        if (seen[other] || tree_joint[j]) continue;
        seen[other] = 1;
        tree_joint[j] = 1;
        t.parent_joint[other] = j;
        t.parent_body[other] = b;
        t.forward[other] = a == b ? 1 : 0;
        queue.push_back(other);
      }
    }
  };
  auto root = [&](int b) {
    if (seen[b]) return;
    seen[b] = 1;
    queue.push_back(b);
  };
  for (const auto& s : m.supports)
    if (std::all_of(s.fixed.begin(), s.fixed.end(), [](bool f) { return f; })) root(t.body_of_node[s.node]);
  grow();
  for (const auto& s : m.supports) root(t.body_of_node[s.node]), grow();
  for (int n = 0; n < nn; ++n) root(t.body_of_node[n]), grow();
  for (std::size_t j = 0; j < m.joints.size(); ++j)
    if (!tree_joint[j]) t.loops.push_back(static_cast<int>(j));
  return t;
}

// The joint's relative motion (solvers/pose.hpp): translation d and rotation P.
Vec3 joint_translation(const Joint& j, const double* q) {
  Vec3 d = Vec3::Zero();
  for (int k = 0; k < j.translations; ++k) d += q[k] * j.axes[k];
  return d;
}

Mat3 joint_rotation(const Joint& j, const double* q) {
  if (j.type == JointType::Spherical) {
    Vec3 s = Vec3::Zero();
    for (int k = 0; k < 3; ++k) s += q[k] * j.axes[k];
    return exp_so3(s);
  }
  Mat3 P = Mat3::Identity();
  for (int k = j.translations; k < j.coordinates(); ++k) P = P * exp_so3(q[k] * j.axes[k]);
  return P;
}

// The spin (in body A's frame) that coordinate k of the joint adds to R_A P: R_B = R_A P, and
// dR_B = [R_A w_k] R_B dq_k. Translations: zero.
Vec3 joint_spin(const Joint& j, const double* q, int k) {
  if (k < j.translations) return Vec3::Zero();
  if (j.type == JointType::Spherical) {
    Vec3 s = Vec3::Zero();
    for (int c = 0; c < 3; ++c) s += q[c] * j.axes[c];
    return tangent_so3(s) * j.axes[k];
  }
  Mat3 E = Mat3::Identity();
  for (int c = j.translations; c < k; ++c) E = E * exp_so3(q[c] * j.axes[c]);
  return E * j.axes[k];
}

struct Frames {
  std::vector<Mat3> R;
  std::vector<Vec3> t;
};

void forward_kinematics(const Model& m, const Topology& top, const Eigen::VectorXd& q, Frames& f) {
  f.R.assign(top.bodies, Mat3::Identity());
  f.t.assign(top.bodies, Vec3::Zero());
  for (const int b : top.order) {
    const int j = top.parent_joint[b];
    if (j < 0) continue;
    const auto& jt = m.joints[j];
    const double* qj = q.data() + top.offset[j];
    const Vec3& X = m.nodes[jt.nodes[0]].x;
    const int p = top.parent_body[b];
    const Mat3 P = joint_rotation(jt, qj);
    const Vec3 d = joint_translation(jt, qj);
    if (top.forward[b]) {  // b = B: R_B = R_A P, x_B(X) = x_A(X) + R_A d
      f.R[b] = f.R[p] * P;
      f.t[b] = f.R[p] * (X + d) + f.t[p] - f.R[b] * X;
    } else {  // b = A: R_A = R_B P^T, x_A(X) = x_B(X) - R_A d
      f.R[b] = f.R[p] * P.transpose();
      f.t[b] = f.R[p] * X + f.t[p] - f.R[b] * (d + X);
    }
  }
}

// One block of equations: a loop joint's six rows or a node target's three or six.
struct Equation {
  bool loop = false;
  int index = -1;  // the joint, or the target in Pose::nodes
  int row = 0;
  int rows = 0;
};

struct Unknown {
  int joint = -1;
  int coordinate = 0;
  int flat = 0;      // in the vector of all coordinates
  double scale = 1;  // the length scale for a translation (unknowns are made dimensionless)
};

class PoseProblem {
 public:
  PoseProblem(const Model& m, const Pose& pose, const PoseOptions& o) : m_(m), pose_(pose), o_(o), top_(topology_of(m)) {
    L_ = m.length_scale();
    given_ = Eigen::VectorXd::Zero(top_.coordinates);
    std::vector<char> is_given(top_.coordinates, 0);
    for (const auto& [j, v] : pose.joints)
      for (int k = 0; k < v.size(); ++k) given_[top_.offset[j] + k] = v[k], is_given[top_.offset[j] + k] = 1;
    // Equations and the joints each depends on.
    std::vector<char> involved(m.joints.size(), 0);
    auto mark_path = [&](int b, std::vector<int>& count) {
      for (; top_.parent_joint[b] >= 0; b = top_.parent_body[b]) ++count[top_.parent_joint[b]];
    };
    int rows = 0;
    for (const int j : top_.loops) {
      equations_.push_back({true, j, rows, 6});
      rows += 6;
      std::vector<int> count(m.joints.size(), 0);
      mark_path(top_.body_of_node[m.joints[j].nodes[0]], count);
      mark_path(top_.body_of_node[m.joints[j].nodes[1]], count);
      for (std::size_t i = 0; i < count.size(); ++i) involved[i] |= count[i] == 1;  // not on both paths
      involved[j] = 1;
    }
    for (std::size_t k = 0; k < pose.nodes.size(); ++k) {
      const int r = pose.nodes[k].has_rotation ? 6 : 3;
      equations_.push_back({false, static_cast<int>(k), rows, r});
      rows += r;
      std::vector<int> count(m.joints.size(), 0);
      mark_path(top_.body_of_node[pose.nodes[k].node], count);
      for (std::size_t i = 0; i < count.size(); ++i) involved[i] |= count[i] > 0;
    }
    rows_ = rows;
    const bool targets = !pose.nodes.empty();
    for (std::size_t j = 0; j < m.joints.size(); ++j) {
      const auto& jt = m.joints[j];
      if (!involved[j] || jt.type == JointType::VirtualSpring) continue;
      for (int k = 0; k < jt.coordinates(); ++k) {
        const int flat = top_.offset[j] + k;
        if (is_given[flat] || (jt.stiffness[k] > 0.0 && !targets)) continue;
        unknowns_.push_back({static_cast<int>(j), k, flat, jt.is_translation(k) ? L_ : 1.0});
      }
    }
    cod_.setThreshold(o_.rank_tolerance);
  }

  PoseSolution solve() {
    PoseSolution s;
    Eigen::VectorXd q = given_;
    if (rows_ > 0) q = continuation(s);
    check_limits(q);
    Frames f;
    forward_kinematics(m_, top_, q, f);
    s.q.resize(m_.joints.size());
    for (std::size_t j = 0; j < m_.joints.size(); ++j) s.q[j] = q.segment(top_.offset[j], m_.joints[j].coordinates());
    s.body_of_node = top_.body_of_node;
    s.R = std::move(f.R);
    s.t = std::move(f.t);
    return s;
  }

 private:
  // Target position and rotation at lambda.
  Vec3 target_xyz(const PoseTarget& t, double lambda) const { return m_.nodes[t.node].x + lambda * (t.xyz - m_.nodes[t.node].x); }
  Mat3 target_rotation(const PoseTarget& t, double lambda) const { return exp_so3(lambda * log_so3(t.rotation)); }

  // Scaled residual at q and lambda (positions over L).
  void residual(const Eigen::VectorXd& q, double lambda, const Frames& f, Eigen::VectorXd& r) const {
    r.resize(rows_);
    for (const auto& e : equations_) {
      if (e.loop) {
        const auto& jt = m_.joints[e.index];
        const double* qj = q.data() + top_.offset[e.index];
        const int a = top_.body_of_node[jt.nodes[0]], b = top_.body_of_node[jt.nodes[1]];
        const Vec3& X = m_.nodes[jt.nodes[0]].x;
        r.segment<3>(e.row) = (f.R[a] * (X + joint_translation(jt, qj)) + f.t[a] - f.R[b] * X - f.t[b]) / L_;
        r.segment<3>(e.row + 3) = log_so3(f.R[a] * joint_rotation(jt, qj) * f.R[b].transpose());
      } else {
        const auto& t = pose_.nodes[e.index];
        const int b = top_.body_of_node[t.node];
        r.segment<3>(e.row) = (f.R[b] * m_.nodes[t.node].x + f.t[b] - target_xyz(t, lambda)) / L_;
        if (t.has_rotation) r.segment<3>(e.row + 3) = log_so3(f.R[b] * target_rotation(t, lambda).transpose());
      }
    }
  }

  // The twist (spin w, velocity v of the point at the origin) that unknown u gives body b, zero
  // when u's joint is not on b's path to its root.
  bool twist(const Eigen::VectorXd& q, const Frames& f, const Unknown& u, int b, Vec3& w, Vec3& v) const {
    for (; top_.parent_joint[b] >= 0; b = top_.parent_body[b]) {
      if (top_.parent_joint[b] != u.joint) continue;
      const auto& jt = m_.joints[u.joint];
      const int a = top_.body_of_node[jt.nodes[0]], c = top_.body_of_node[jt.nodes[1]];
      const double* qj = q.data() + top_.offset[u.joint];
      const double sign = top_.forward[b] ? 1.0 : -1.0;  // met from nodes[1]: the inverse motion
      if (jt.is_translation(u.coordinate)) {
        w.setZero();
        v = sign * (f.R[a] * jt.axes[u.coordinate]);
      } else {
        const Vec3 p = f.R[c] * m_.nodes[jt.nodes[1]].x + f.t[c];  // the joint's point on body B
        w = sign * (f.R[a] * joint_spin(jt, qj, u.coordinate));
        v = -w.cross(p);
      }
      return true;
    }
    return false;
  }

  // Scaled Jacobian of the residual over the scaled unknowns. Rotation rows use d log(M) ~ dM M^T,
  // exact where M = I (a closed loop, a reached rotation): Newton converges to the same solution.
  void jacobian(const Eigen::VectorXd& q, const Frames& f, Eigen::MatrixXd& J) const {
    J.setZero(rows_, static_cast<Eigen::Index>(unknowns_.size()));
    for (std::size_t c = 0; c < unknowns_.size(); ++c) {
      const Unknown& u = unknowns_[c];
      Vec3 w, v;
      for (const auto& e : equations_) {
        Vec3 dx = Vec3::Zero(), dw = Vec3::Zero();
        if (e.loop) {
          const auto& jt = m_.joints[e.index];
          const int a = top_.body_of_node[jt.nodes[0]], b = top_.body_of_node[jt.nodes[1]];
          const double* qj = q.data() + top_.offset[e.index];
          const Vec3& X = m_.nodes[jt.nodes[0]].x;
          const Vec3 pa = f.R[a] * (X + joint_translation(jt, qj)) + f.t[a];
          const Vec3 pb = f.R[b] * X + f.t[b];
          if (twist(q, f, u, a, w, v)) dx += w.cross(pa) + v, dw += w;
          if (twist(q, f, u, b, w, v)) dx -= w.cross(pb) + v, dw -= w;
          if (u.joint == e.index) {
            if (jt.is_translation(u.coordinate)) dx += f.R[a] * jt.axes[u.coordinate];
            else dw += f.R[a] * joint_spin(jt, qj, u.coordinate);
          }
        } else {
          const auto& t = pose_.nodes[e.index];
          const int b = top_.body_of_node[t.node];
          if (twist(q, f, u, b, w, v)) dx = w.cross(f.R[b] * m_.nodes[t.node].x + f.t[b]) + v, dw = w;
        }
        J.block<3, 1>(e.row, c) = dx * u.scale / L_;
        if (e.rows == 6) J.block<3, 1>(e.row + 3, c) = dw * u.scale;
      }
    }
  }

  // Newton at lambda from q (the predictor), in place. False: not converged. The Jacobian's
  // decomposition is kept from iterate to iterate and from step to step (a chord iteration,
  // Kelley 2003, "Solving Nonlinear Equations with Newton's Method", sec. 1.8 and 2.3) while
  // each residual is at most kChordContraction times the one before (at a rate that reaches the
  // goal within the iterations allowed); otherwise it is made anew at the current iterate. Steps short of the pose converge to kStepTolerance and their rank is
  // checked on the decomposition in hand (a nearby point's). At the pose (lambda = 1) the Jacobian
  // is made at the converged iterate, its rank checked, and one Newton step taken with it: the
  // solution is then accurate to rounding (quadratic convergence), not just to the tolerance.
  bool newton(Eigen::VectorXd& q, double lambda, PoseSolution& s) {
    set_given(q, lambda);
    if (unknowns_.empty()) {  // nothing to solve: the given coordinates close the loops or not
      forward_kinematics(m_, top_, q, f_);
      residual(q, lambda, f_, r_);
      return r_.lpNorm<Eigen::Infinity>() <= o_.tolerance;
    }
    const auto n = static_cast<Eigen::Index>(unknowns_.size());
    double first = -1.0, last = std::numeric_limits<double>::infinity();
    for (int it = 0; it <= o_.max_newton_iterations; ++it) {
      forward_kinematics(m_, top_, q, f_);
      residual(q, lambda, f_, r_);
      const double norm = r_.lpNorm<Eigen::Infinity>();
      if (!std::isfinite(norm)) return false;
      if (first < 0.0) first = norm;
      const bool last_step = lambda == 1.0;
      const double goal = last_step ? o_.tolerance : std::max(o_.tolerance, kStepTolerance);
      if (norm <= goal) {
        if (!decomposed_ || last_step) decompose(q, s);
        if (cod_.rank() < n) singular(J_);
        if (last_step) update(q, s);
        return true;
      }
      if (it == o_.max_newton_iterations || norm > kDivergence * std::max(first, o_.tolerance)) return false;
      // A chord step that shrank the residual too little, or at a rate that would not reach the
      // goal within the iterations left, gives way to a Jacobian at the iterate.
      const double rate = norm / last;
      if (!decomposed_ || rate > kChordContraction ||
          (rate > 0.0 && std::log(goal / norm) / std::log(rate) > o_.max_newton_iterations - it))
        decompose(q, s);
      update(q, s);
      last = norm;
    }
    return false;
  }

  // The given coordinates at lambda.
  void set_given(Eigen::VectorXd& q, double lambda) const {
    for (const auto& [j, v] : pose_.joints)
      for (int k = 0; k < v.size(); ++k) q[top_.offset[j] + k] = lambda * v[k];
  }

  // q -= J^+ r (r_, the residual at q), in the unknowns' scales.
  void update(Eigen::VectorXd& q, PoseSolution& s) {
    dx_.noalias() = pinv_ * r_;
    for (std::size_t c = 0; c < unknowns_.size(); ++c) q[unknowns_[c].flat] -= dx_[c] * unknowns_[c].scale;
    ++s.newton_iterations;
  }

  // The Jacobian at q (the frames f_ at q) and its decomposition.
  void decompose(const Eigen::VectorXd& q, PoseSolution& s) {
    ++s.jacobians;
    jacobian(q, f_, J_);
    cod_.compute(J_);
    // The least-squares solution operator, so that each chord step is a product. At full column
    // rank J P = Q T (Z = I), and J's pseudo-inverse P T^-1 Q^T[:n] = P T^-1 T^-T P^T J^T (the
    // semi-normal equations, Golub & Van Loan 2013, sec. 5.3.8: no Q is formed).
    const auto n = static_cast<Eigen::Index>(unknowns_.size());
    if (cod_.rank() == n) {
      const auto T = cod_.matrixT().topLeftCorner(n, n).triangularView<Eigen::Upper>();
      pinv_ = cod_.colsPermutation().transpose() * J_.transpose();
      T.transpose().solveInPlace(pinv_);
      T.solveInPlace(pinv_);
      pinv_ = cod_.colsPermutation() * pinv_;
    } else {
      pinv_ = cod_.pseudoInverse();
    }
    decomposed_ = true;
  }

  // The pose leaves some unknowns undetermined: name the coordinate that moves most along the
  // Jacobian's null space.
  [[noreturn]] void singular(const Eigen::MatrixXd& J) const {
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeFullV);
    const Eigen::VectorXd n = svd.matrixV().col(svd.matrixV().cols() - 1);
    Eigen::Index c = 0;
    n.cwiseAbs().maxCoeff(&c);
    const Unknown& u = unknowns_[c];
    throw ModelError("joint '" + m_.joints[u.joint].id + "' coordinate " + std::to_string(u.coordinate),
                     "the pose does not determine this coordinate (a singular pose, or fewer node targets and joint "
                     "values than free coordinates: give it in \"pose\".\"joints\", or a target)");
  }

  // The number of continuation steps: the largest change per step within the options' limits.
  int first_steps() const {
    double measure = 0.0;
    for (const auto& [j, v] : pose_.joints)
      for (int k = 0; k < v.size(); ++k)
        measure = std::max(measure, std::abs(v[k]) / (m_.joints[j].is_translation(k) ? o_.max_step_length * L_ : o_.max_step_angle));
    for (const auto& t : pose_.nodes) {
      measure = std::max(measure, (t.xyz - m_.nodes[t.node].x).norm() / (o_.max_step_length * L_));
      if (t.has_rotation) measure = std::max(measure, log_so3(t.rotation).norm() / o_.max_step_angle);
    }
    return std::max(1, static_cast<int>(std::ceil(measure)));
  }

  Eigen::VectorXd continuation(PoseSolution& s) {
    Eigen::VectorXd q = Eigen::VectorXd::Zero(top_.coordinates), previous = q;
    const double h_max = 1.0 / first_steps();
    double lambda = 0.0, h = h_max, h_last = 0.0;
    if (unknowns_.empty()) {
      if (!newton(q, 1.0, s)) unreachable(0.0);
      return q;
    }
    const double h_min = h_max * std::ldexp(1.0, -o_.max_halvings);
    while (lambda < 1.0) {
      const double next = std::min(1.0, lambda + h);
      Eigen::VectorXd trial = q;
      if (h_last > 0.0) trial += (next - lambda) / h_last * (q - previous);  // secant predictor
      if (newton(trial, next, s)) {
        previous = q;
        q = trial;
        h_last = next - lambda;
        lambda = next;
        ++s.steps;
        h = std::min(h_max, kStepGrowth * h);
        continue;
      }
      h /= 2.0;
      if (h < h_min) {
        // The residual that names the culprit: the last solution's against the smallest step's
        // demands (the given coordinates and the targets at `next`), not Newton's last iterate.
        set_given(q, next);
        forward_kinematics(m_, top_, q, f_);
        residual(q, next, f_, r_);
        unreachable(lambda);
      }
    }
    return q;
  }

  // Newton failed in the smallest step: name the equation with the largest residual.
  [[noreturn]] void unreachable(double lambda) const {
    const Equation* worst = &equations_.front();
    double largest = -1.0;
    for (const auto& e : equations_) {
      const double n = r_.size() == rows_ ? r_.segment(e.row, e.rows).norm() : 0.0;
      if (n > largest) largest = n, worst = &e;
    }
    const std::string reached = unknowns_.empty() ? std::string("every coordinate it depends on is given") :
                                "reached from the reference only up to " + std::to_string(static_cast<int>(100.0 * lambda)) +
                                "% of the way (continuation in steps down to 1/" +
                                std::to_string(static_cast<long>(std::ldexp(1.0, o_.max_halvings) * first_steps())) + ")";
    if (worst->loop)
      throw ModelError("joint '" + m_.joints[worst->index].id + "'",
                       "the loop this joint closes cannot close at the pose: " + reached);
    throw ModelError("node '" + m_.nodes[pose_.nodes[worst->index].node].id + "'",
                     "the target is beyond reach of the mechanism: " + reached);
  }

  void check_limits(const Eigen::VectorXd& q) const {
    for (std::size_t j = 0; j < m_.joints.size(); ++j) {
      const auto& jt = m_.joints[j];
      for (std::size_t k = 0; k < jt.limits.size(); ++k) {
        const double v = q[top_.offset[j] + static_cast<int>(k)];
        const auto [lo, hi] = jt.limits[k];
        if (v < lo || v > hi)
          throw ModelError("joint '" + jt.id + "' coordinate " + std::to_string(k),
                           fmt::format("the pose needs {}, outside its limits [{}, {}]", v, lo, hi));
      }
    }
  }

  const Model& m_;
  const Pose& pose_;
  const PoseOptions& o_;
  Topology top_;
  double L_ = 1.0;
  Eigen::VectorXd given_;
  std::vector<Equation> equations_;
  std::vector<Unknown> unknowns_;
  int rows_ = 0;
  Eigen::VectorXd r_;  // the last residual evaluated
  // Newton's workspace, kept from iteration to iteration and step to step.
  Frames f_;
  Eigen::MatrixXd J_;
  Eigen::VectorXd dx_;
  Eigen::MatrixXd pinv_;  // J_'s pseudo-inverse
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod_;
  bool decomposed_ = false;  // cod_ holds the decomposition of J_
};

}  // namespace

PoseSolution solve_pose(const Model& model, const Pose& pose, const PoseOptions& options) {
  options.validate();
  PoseProblem problem(model, pose, options);
  return problem.solve();
}

}  // namespace beamfea
