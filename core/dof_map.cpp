#include "core/dof_map.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/errors.hpp"
#include "core/sparse_row.hpp"

namespace beamfea {

Configuration reference_configuration(const Model& m) {
  Configuration c;
  reference_configuration(m, c);
  return c;
}

void reference_configuration(const Model& m, Configuration& c) {
  c.x.clear();
  c.x.reserve(m.nodes.size());
  for (const auto& n : m.nodes) c.x.push_back(n.x);
  c.R.assign(m.nodes.size(), Mat3::Identity());
  c.joint_axes.resize(m.joints.size());
  for (std::size_t j = 0; j < m.joints.size(); ++j) c.joint_axes[j] = m.joints[j].axes;
}

namespace {

using Expr = SparseRow;

// The key of prescribed value p in an elimination's expressions (free DOFs have keys >= 0).
constexpr int prescribed_key(int p) { return -1 - p; }

double max_abs(const Expr& e) {
  double m = 0.0;
  for (const auto& [k, v] : e) m = std::max(m, std::abs(v));
  return m;
}

}  // namespace

void DofMap::rebuild(const Model& model, const Configuration& configuration) {
  // Every member is set afresh below (assign, clear, resize): nothing of the last build's value
  // survives, only its storage.
  model_ = &model;
  n_nodes_ = static_cast<int>(model.nodes.size());
  n_raw_ = 6 * n_nodes_;
  n_ind_ = 0;
  n_free_ = 0;
  joint_offset_.clear();
  joint_offset_.reserve(model.joints.size());
  for (const auto& j : model.joints) {
    joint_offset_.push_back(n_raw_);
    n_raw_ += j.coordinates();
  }
  x_ = configuration.x;  // copy-assigned: the storage is kept when it has room
  build_forest(model);
  build_tree_rows(model, configuration);
  build_extra_rows(model, configuration);
  eliminate(model);
}

int DofMap::raw_index(const DofRef& d) const {
  return d.owner == DofRef::Owner::Node ? raw_node(d.index, d.comp) : raw_joint(d.index, d.comp);
}

DofRef DofMap::raw_ref(int raw) const {
  if (raw < 6 * n_nodes_) return {DofRef::Owner::Node, raw / 6, raw % 6};
  const auto it = std::upper_bound(joint_offset_.begin(), joint_offset_.end(), raw);
  const int j = static_cast<int>(it - joint_offset_.begin()) - 1;
  return {DofRef::Owner::Joint, j, raw - joint_offset_[j]};
}

int DofMap::prescribed_index(int raw) const { return raw_prescribed_[raw]; }

Eigen::VectorXd DofMap::prescribed_values() const {
  Eigen::VectorXd v(prescribed_size());
  for (int i = 0; i < prescribed_size(); ++i) v[i] = prescribed_[i].value;
  return v;
}

// Raw rows of the slaves in terms of independent DOFs, parents first.
//   rigid link p -> s, d = x_s - x_p:  u_s = u_p + theta_p x d,  theta_s = theta_p
//   joint p -> s:                       u_s = u_p,  theta_s = theta_p +/- sum_i a_i dq_i
void DofMap::build_tree_rows(const Model& m, const Configuration& c) {
  raw_to_ind_.assign(n_raw_, -1);
  for (int n = 0; n < n_nodes_; ++n)
    if (!is_slave(n))
      for (int k = 0; k < 6; ++k) raw_to_ind_[6 * n + k] = 0;
  for (int r = 6 * n_nodes_; r < n_raw_; ++r) raw_to_ind_[r] = 0;
  ind_to_raw_.clear();
  ind_to_raw_.reserve(n_raw_);
  for (int r = 0; r < n_raw_; ++r)
    if (raw_to_ind_[r] == 0) {
      raw_to_ind_[r] = static_cast<int>(ind_to_raw_.size());
      ind_to_raw_.push_back(r);
    }
  n_ind_ = static_cast<int>(ind_to_raw_.size());

  // Expressions only for slave DOFs; an independent DOF's row is itself. Each slave row is built
  // in `acc` and stored once finished (RowStore); the rows of a slave are built in the order
  // 3, 4, 5, 0, 1, 2: a virtual spring's lever term of u_s (rows 0..2) reads theta of the first
  // body, which may be the slave itself. Each row receives its terms in the same order as when
  // all six were built side by side, so its sums are the same.
  std::vector<int>& slave_slot = scratch_.slave_slot;
  slave_slot.assign(n_raw_, -1);
  int n_slave_rows = 0;
  for (int ei : tree_order_) {
    const int s = tree_edges_[ei].child;
    for (int k = 0; k < 6; ++k) slave_slot[6 * s + k] = n_slave_rows++;
  }
  RowStore& slave_rows = scratch_.slave_rows;
  slave_rows.reset(n_slave_rows, 4 * static_cast<std::size_t>(n_slave_rows));
  Expr& acc = scratch_.acc;
  Expr& lever = scratch_.lever;
  acc.reserve(16);
  lever.reserve(16);
  auto add_row = [&](Expr& dst, int raw, double f) {
    if (raw_to_ind_[raw] >= 0) dst[raw_to_ind_[raw]] += f;
    else add_scaled(dst, slave_rows[slave_slot[raw]], f);
  };
  for (int ei : tree_order_) {
    const auto& e = tree_edges_[ei];
    const int p = e.parent, s = e.child;
    for (int row : {3, 4, 5, 0, 1, 2}) {
      acc.clear();
      add_row(acc, 6 * p + row, 1.0);
      if (e.kind == ConstraintEdge::Kind::Rigid) {
        if (row < 3) {
          const Mat3 D = -skew(c.x[s] - c.x[p]);  // u_s += -[d] theta_p
          for (int k = 0; k < 3; ++k)
            if (D(row, k) != 0.0) add_row(acc, 6 * p + 3 + k, D(row, k));
        }
      } else {
        const double sign = e.forward ? 1.0 : -1.0;
        const auto& axes = c.joint_axes[e.index];
        const int nt = m.joints[e.index].translations;
        for (int q = 0; q < static_cast<int>(axes.size()); ++q) {
          const int offset = q < nt ? 0 : 3;  // translations move u, rotations move theta
          const int i = row - offset;
          if (i >= 0 && i < 3 && axes[q][i] != 0.0) add_row(acc, raw_joint(e.index, q), sign * axes[q][i]);
        }
        // A joint with translations (a virtual spring) separates its nodes in a deformed
        // configuration: the offset d = x_s - x_p turns with the first body, so
        // u_s += -[d] theta_1, theta_1 = theta_p (forward) or theta_s (reverse). Zero in the reference.
        const Vec3 d = c.x[s] - c.x[p];
        if (row < 3 && d.squaredNorm() > 0.0) {
          const Mat3 D = -skew(d);
          const int body1 = e.forward ? p : s;
          lever.clear();
          for (int k = 0; k < 3; ++k)
            if (D(row, k) != 0.0) add_row(lever, 6 * body1 + 3 + k, D(row, k));
          add_scaled(acc, lever, 1.0);
        }
      }
      slave_rows.set(slave_slot[6 * s + row], acc);
    }
  }
  // Tind_ row by row (its terms are sorted and unique already).
  std::size_t nnz = 0;
  for (int r = 0; r < n_raw_; ++r) {
    if (raw_to_ind_[r] >= 0) ++nnz;
    else for (const auto& [k, v] : slave_rows[slave_slot[r]]) nnz += v != 0.0 ? 1 : 0;
  }
  Tind_.resize(n_raw_, n_ind_);
  Tind_.reserve(static_cast<Eigen::Index>(nnz));
  for (int r = 0; r < n_raw_; ++r) {
    Tind_.startVec(r);
    if (raw_to_ind_[r] >= 0) {
      Tind_.insertBack(r, raw_to_ind_[r]) = 1.0;
      continue;
    }
    for (const auto& [k, v] : slave_rows[slave_slot[r]])
      if (v != 0.0) Tind_.insertBack(r, k) = v;
  }
  Tind_.finalize();
}

// Row k (0..5) of a loop edge over raw DOFs, from nodes[0] (parent) to nodes[1] (child).
void DofMap::edge_row_raw(const Model& m, const Configuration& c, const ConstraintEdge& e, int k, Row& row) const {
  row.clear();
  const int p = e.parent, s = e.child;
  const int i = k % 3;
  row.push_back({6 * s + k, 1.0});
  row.push_back({6 * p + k, -1.0});
  if (k < 3 && e.kind == ConstraintEdge::Kind::Rigid) {
    const Mat3 D = skew(c.x[s] - c.x[p]);  // u_s - u_p + [d] theta_p = 0
    for (int j = 0; j < 3; ++j)
      if (D(k, j) != 0.0) row.push_back({6 * p + 3 + j, D(k, j)});
  }
  if (e.kind == ConstraintEdge::Kind::Joint) {
    // u_s - u_p - sum_t a_t q_t = 0 and theta_s - theta_p - sum_r a_r q_r = 0
    const auto& axes = c.joint_axes[e.index];
    const int nt = m.joints[e.index].translations;
    for (int q = 0; q < static_cast<int>(axes.size()); ++q)
      if ((q < nt) == (k < 3) && axes[q][i] != 0.0) row.push_back({raw_joint(e.index, q), -axes[q][i]});
  }
}

void DofMap::build_extra_rows(const Model& m, const Configuration& c) {
  // Prescribed values: supports first (value 0), then "prescribed" entries override values.
  raw_prescribed_.assign(n_raw_, -1);
  prescribed_.clear();
  auto prescribe = [&](int raw, double value, bool support) {
    int& p = raw_prescribed_[raw];
    if (p < 0) {
      p = static_cast<int>(prescribed_.size());
      prescribed_.push_back({raw_ref(raw), value, support});
    } else {
      if (!support) prescribed_[p].value = value;
      prescribed_[p].support = prescribed_[p].support || support;
    }
  };
  for (const auto& s : m.supports)
    for (int k = 0; k < 6; ++k)
      if (s.fixed[k] && !s.skewed) prescribe(6 * s.node + k, 0.0, true);
  for (const auto& p : m.prescribed) prescribe(raw_index(p.dof), p.value, false);
  // The values of the linear constraints: prescribed values that hold no raw DOF.
  for (std::size_t c = 0; c < m.constraints.size(); ++c) {
    const auto& lc = m.constraints[c];
    prescribed_.push_back({lc.terms.empty() ? DofRef{} : lc.terms[0].dof, lc.value, false, static_cast<int>(c)});
  }

  ind_prescribed_.assign(n_ind_, -1);
  // The rows are counted first and written over the last build's rows (their vectors keep their
  // storage): a prescribed value on a slave, then six rows per loop edge.
  // The user rows (skewed supports, ties, linear constraints) come last: a redundant one is then
  // the user's to remove, never a loop's.
  std::size_t n_extra = 6 * loop_edges_.size() + m.constraints.size();
  for (int r = 0; r < n_raw_; ++r)
    if (raw_prescribed_[r] >= 0 && raw_to_ind_[r] < 0) ++n_extra;
  for (const auto& s : m.supports)
    if (s.skewed) n_extra += static_cast<std::size_t>(std::count(s.fixed.begin(), s.fixed.end(), true));
  for (const auto& t : m.ties) n_extra += static_cast<std::size_t>(std::count(t.dofs.begin(), t.dofs.end(), true));
  extra_.resize(n_extra);
  std::size_t next = 0;
  auto new_row = [&]() -> ExtraRow& { return next_extra_row(next); };
  for (int r = 0; r < n_raw_; ++r) {
    const int p = raw_prescribed_[r];
    if (p < 0) continue;
    if (raw_to_ind_[r] >= 0) {
      ind_prescribed_[raw_to_ind_[r]] = p;
    } else {
      ExtraRow& x = new_row();
      x.raw.push_back({r, 1.0});
      x.rhs.push_back({p, 1.0});
      x.prescribed = p;
    }
  }
  for (int li = 0; li < static_cast<int>(loop_edges_.size()); ++li)
    for (int k = 0; k < 6; ++k) {
      const auto& e = loop_edges_[li];
      ExtraRow& x = new_row();
      edge_row_raw(m, c, e, k, x.raw);
      x.loop = li;
      x.joint_row = k;
      if (e.kind == ConstraintEdge::Kind::Joint) x.joint = e.index;
    }
  build_user_rows(m, next);
}

DofMap::ExtraRow& DofMap::next_extra_row(std::size_t& next) {
  ExtraRow& x = extra_[next++];
  x.raw.clear();
  x.rhs.clear();
  x.joint = x.joint_row = x.prescribed = x.loop = -1;
  x.support = x.tie = x.constraint = x.comp = -1;
  return x;
}

void DofMap::eliminate(const Model& m) {
  eliminate_extra_rows(m);
  number_free_dofs();
  build_transforms();
}

const SparseRow* DofMap::dependent_expr(int ind) const {
  const int slot = scratch_.dependent_slot[ind];
  return slot >= 0 ? &scratch_.dependent[slot] : nullptr;
}

// Gauss-Jordan elimination of the extra constraints on the independent DOFs; prescribed
// independent DOFs are known values, encoded as keys prescribed_key(p) = -1 - p in the expressions.
// The expression of a dependent DOF d over free independent DOFs (keys >= 0) and prescribed values
// is scratch_.dependent[scratch_.dependent_slot[d]] (slots in the order of elimination).
void DofMap::eliminate_extra_rows(const Model& m) {
  std::vector<Expr>& dependent = scratch_.dependent;
  std::vector<int>& dependent_slot = scratch_.dependent_slot;
  std::vector<int>& dependent_ind = scratch_.dependent_ind;
  dependent_slot.assign(n_ind_, -1);
  dependent_ind.clear();
  // The redundant rows and their names are written over the last build's (n_names, n_rows of
  // them), and the vectors cut to size at the end: a rebuild with the same redundancy allocates
  // nothing for them.
  std::size_t n_names = 0, n_rows = 0;
  extra_ind_.resize(extra_.size());
  Expr& row = scratch_.row;  // row . ind - rhs . p = 0
  Expr& e = scratch_.e;
  Expr& expr = scratch_.expr;
  for (std::size_t xi = 0; xi < extra_.size(); ++xi) {
    const ExtraRow& x = extra_[xi];
    row.clear();
    for (const auto& t : x.raw)
      for (SparseRowMatrix::InnerIterator it(Tind_, t.ind); it; ++it) row[static_cast<int>(it.col())] += t.coef * it.value();
    extra_ind_[xi] = row;  // copy-assigned into the last build's storage
    for (const auto& t : x.rhs) row[prescribed_key(t.ind)] -= t.coef;
    const double scale = max_abs(row);
    // Known values and earlier eliminations.
    e.clear();
    for (const auto& [k, v] : row) {
      if (k < 0) {
        e[k] += v;
      } else if (ind_prescribed_[k] >= 0) {
        e[prescribed_key(ind_prescribed_[k])] += v;
      } else if (const Expr* d = dependent_expr(k)) {
        add_scaled(e, *d, v);
      } else {
        e[k] += v;
      }
    }
    int pivot = -1;
    double best = 1e-10 * scale;
    for (const auto& [k, v] : e)
      if (k >= 0 && std::abs(v) > best) {
        best = std::abs(v);
        pivot = k;
      }
    if (pivot < 0) {
      if (is_user_row(x)) reject_user_row(m, x, e, scale);
      add_redundant_row(m, x, e, scale, n_names, n_rows);
      continue;
    }
    const double cp = e[pivot];
    expr.clear();
    for (const auto& [k, v] : e)
      if (k != pivot && std::abs(v) > 1e-14 * scale) expr[k] = -v / cp;
    // Each earlier expression is updated on its own: the order of this loop changes no sum.
    for (const int d : dependent_ind) {
      Expr& de = dependent[dependent_slot[d]];
      auto it = de.find(pivot);
      if (it == de.end()) continue;
      const double f = it->second;
      de.erase(it);
      add_scaled(de, expr, f);
    }
    // The pivot was free (its key survived the substitutions above): it gets the next slot, whose
    // storage is swapped with `expr`'s.
    const int slot = static_cast<int>(dependent_ind.size());
    if (static_cast<std::size_t>(slot) == dependent.size()) dependent.emplace_back();
    std::swap(dependent[slot], expr);
    dependent_slot[pivot] = slot;
    dependent_ind.push_back(pivot);
  }

  redundant_names_.resize(n_names);
  redundant_.resize(n_rows);
  redundant_what_.resize(n_rows);
}

// Extra row `x` reduced to `e`, with no free DOF left: it is named, and where it still involves
// prescribed values, kept as a row those values must satisfy (check_consistency).
void DofMap::add_redundant_row(const Model& m, const ExtraRow& x, const SparseRow& e, double scale, std::size_t& n_names,
                               std::size_t& n_rows) {
  if (n_names == redundant_names_.size()) redundant_names_.emplace_back();
  std::string& name = redundant_names_[n_names++];
  describe_extra(m, x, name);
  if (n_rows == redundant_.size()) {
    redundant_.emplace_back();
    redundant_what_.emplace_back();
  }
  Row& r = redundant_[n_rows];
  r.clear();
  for (const auto& [k, v] : e)
    if (k < 0 && std::abs(v) > 1e-10 * scale) r.push_back({-1 - k, v});
  if (!r.empty()) redundant_what_[n_rows++] = name;
}

// The free DOFs: the independent ones neither prescribed nor eliminated.
void DofMap::number_free_dofs() {
  raw_to_free_.assign(n_raw_, -1);
  std::vector<int>& ind_to_free = scratch_.ind_to_free;
  ind_to_free.assign(n_ind_, -1);
  free_refs_.clear();
  free_refs_.reserve(n_ind_);
  for (int i = 0; i < n_ind_; ++i) {
    if (ind_prescribed_[i] >= 0 || scratch_.dependent_slot[i] >= 0) continue;
    ind_to_free[i] = n_free_++;
    raw_to_free_[ind_to_raw_[i]] = ind_to_free[i];
    free_refs_.push_back(raw_ref(ind_to_raw_[i]));
  }
  ind_dependent_.assign(n_ind_, 0);
  for (const int d : scratch_.dependent_ind) ind_dependent_[d] = 1;
}

// Tf_ and Tp_ row by row: a row's terms in the order they are produced, then sorted, duplicates
// summed and zeros dropped (append_row).
void DofMap::build_transforms() {
  const std::vector<int>& ind_to_free = scratch_.ind_to_free;
  std::vector<SparseRow::Term>& tf = scratch_.tf;
  std::vector<SparseRow::Term>& tp = scratch_.tp;
  tf.clear();
  tp.clear();
  tf.reserve(16);
  tp.reserve(16);
  auto emit = [&](int k, double v) {
    if (k < 0) tp.emplace_back(-1 - k, v);
    else tf.emplace_back(ind_to_free[k], v);
  };
  Tf_.resize(n_raw_, n_free_);
  Tp_.resize(n_raw_, prescribed_size());
  Tf_.reserve(Tind_.nonZeros());
  Tp_.reserve(prescribed_size());
  for (int r = 0; r < n_raw_; ++r) {
    for (SparseRowMatrix::InnerIterator it(Tind_, r); it; ++it) {
      const int ind = static_cast<int>(it.col());
      if (ind_prescribed_[ind] >= 0) {
        emit(prescribed_key(ind_prescribed_[ind]), it.value());
      } else if (const Expr* d = dependent_expr(ind)) {
        for (const auto& [k, v] : *d) emit(k, it.value() * v);
      } else {
        emit(ind, it.value());
      }
    }
    append_row(Tf_, r, tf);
    append_row(Tp_, r, tp);
  }
  Tf_.finalize();
  Tp_.finalize();
}

void DofMap::describe_extra(const Model& m, const ExtraRow& x, std::string& out) const {
  // Appended piece by piece into `out` (no temporary strings).
  auto append_edge_name = [&](const ConstraintEdge& e) {
    const bool rigid = e.kind == ConstraintEdge::Kind::Rigid;
    out.append(rigid ? "element '" : "joint '").append(rigid ? m.elements[e.index].id : m.joints[e.index].id).append("'");
  };
  out.clear();
  if (x.prescribed >= 0) {
    // A support or prescribed value on a slave node: name the link or joint that carries the node.
    const DofRef& d = prescribed_[x.prescribed].dof;
    out.append(m.describe(d));
    if (d.owner == DofRef::Owner::Node && is_slave(d.index)) {
      out.append(" (carried by ");
      append_edge_name(tree_edges_[parent_edge_[d.index]]);
      out.append(")");
    }
    return;
  }
  if (x.support >= 0) {
    out.append("skewed support at node '").append(m.nodes[m.supports[x.support].node].id).append("' ");
    out.append(kDofNames[x.comp]).append(" (in its axes)");
    return;
  }
  if (x.tie >= 0) {
    const Tie& t = m.ties[x.tie];
    out.append("tie of node '").append(m.nodes[t.nodes[1]].id).append("' to node '").append(m.nodes[t.nodes[0]].id);
    out.append("' ").append(kDofNames[x.comp]);
    return;
  }
  if (x.constraint >= 0) {
    out.append("linear constraint ").append(std::to_string(x.constraint));
    return;
  }
  append_edge_name(loop_edges_[x.loop]);
  out.append(" ").append(kDofNames[x.joint_row]);
}

Eigen::VectorXd DofMap::expand(const Eigen::VectorXd& u_free, const Eigen::VectorXd& u_prescribed) const {
  Eigen::VectorXd u;
  expand(u_free, u_prescribed, u);
  return u;
}

void DofMap::expand(const Eigen::VectorXd& u_free, const Eigen::VectorXd& u_prescribed, Eigen::VectorXd& u) const {
  // Row-major rows: each entry is its row's sum added once, with or without a temporary.
  u.noalias() = Tf_ * u_free;
  if (prescribed_size() > 0) u.noalias() += Tp_ * u_prescribed;
}

}  // namespace beamfea
