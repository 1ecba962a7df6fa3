#include "solvers/fill_ordering.hpp"

#include <algorithm>
#include <cstring>

namespace beamfea {

namespace {

// Both triangles of the symmetric pattern whose lower triangle is `lower`, diagonal included,
// rows sorted within each column (CSC).
struct FullPattern {
  std::vector<int> start, row;
  const int* begin(int j) const { return row.data() + start[j]; }
  int size(int j) const { return start[j + 1] - start[j]; }
};

FullPattern full_pattern(const SparseMatrix& lower) {
  const int n = static_cast<int>(lower.cols());
  const int* p = lower.outerIndexPtr();
  const int* r = lower.innerIndexPtr();
  FullPattern f;
  f.start.assign(static_cast<std::size_t>(n) + 1, 0);
  for (int k = 0; k < n; ++k)
    for (int q = p[k]; q < p[k + 1]; ++q) {
      ++f.start[k + 1];
      if (r[q] != k) ++f.start[r[q] + 1];
    }
  for (int j = 0; j < n; ++j) f.start[j + 1] += f.start[j];
  f.row.resize(static_cast<std::size_t>(f.start[n]));
  std::vector<int> next(f.start.begin(), f.start.end() - 1);
  // Column k receives, in increasing k, its upper entries (rows k' < k, placed while column k' is
  // visited) and then its own lower entries: sorted without a sort.
  for (int k = 0; k < n; ++k)
    for (int q = p[k]; q < p[k + 1]; ++q) {
      const int i = r[q];
      f.row[next[k]++] = i;
      if (i != k) f.row[next[i]++] = k;
    }
  return f;
}

std::vector<int> supervariable_starts(const FullPattern& f, int n) {
  std::vector<int> first{0};
  for (int j = 1; j < n; ++j) {
    const bool same = f.size(j) == f.size(j - 1) &&
                      std::memcmp(f.begin(j), f.begin(j - 1), sizeof(int) * static_cast<std::size_t>(f.size(j))) == 0;
    if (!same) first.push_back(j);
  }
  first.push_back(n);
  return first;
}

// The lower triangle of the compressed graph (a vertex per supervariable, an edge where two
// supervariables' columns couple), pattern only, as cholmod_metis and cholmod_nested_dissection
// read it. Null when CHOLMOD cannot allocate it.
cholmod_sparse* compressed_graph(const FullPattern& f, const std::vector<int>& first, cholmod_common& c) {
  const int groups = static_cast<int>(first.size()) - 1;
  std::vector<int> group_of(static_cast<std::size_t>(first.back()));
  for (int g = 0; g < groups; ++g) std::fill(group_of.begin() + first[g], group_of.begin() + first[g + 1], g);
  // Rows are sorted and groups are runs of consecutive columns: the groups of a column's rows are
  // non-decreasing, so duplicates are adjacent.
  std::vector<int> start{0}, row;
  start.reserve(static_cast<std::size_t>(groups) + 1);
  for (int g = 0; g < groups; ++g) {
    const int j = first[g];
    int last = g;
    for (const int* q = f.begin(j); q != f.begin(j) + f.size(j); ++q) {
      const int h = group_of[*q];
      if (h > last) {
        row.push_back(h);
        last = h;
      }
    }
    start.push_back(static_cast<int>(row.size()));
  }
  cholmod_sparse* g = cholmod_allocate_sparse(groups, groups, row.size(), 1, 1, -1, CHOLMOD_PATTERN, &c);
  if (!g) return nullptr;
  std::copy(start.begin(), start.end(), static_cast<int*>(g->p));
  std::copy(row.begin(), row.end(), static_cast<int*>(g->i));
  return g;
}

// Expands an ordering of the supervariables into one of the columns.
std::vector<int> expand(const std::vector<int>& group_perm, const std::vector<int>& first) {
  std::vector<int> perm;
  perm.reserve(static_cast<std::size_t>(first.back()));
  for (const int g : group_perm)
    for (int j = first[g]; j < first[g + 1]; ++j) perm.push_back(j);
  return perm;
}

}  // namespace

std::vector<int> supervariable_starts(const SparseMatrix& lower) {
  return supervariable_starts(full_pattern(lower), static_cast<int>(lower.cols()));
}

namespace {

// What both orderings start from: the supervariables and the compressed graph (null: none made).
struct Compressed {
  std::vector<int> first;
  cholmod_sparse* graph = nullptr;
};

Compressed compress(const SparseMatrix& lower, cholmod_common& c) {
  Compressed k;
  const int n = static_cast<int>(lower.cols());
  if (n == 0 || lower.rows() != n || !lower.isCompressed()) return k;
  const FullPattern f = full_pattern(lower);
  k.first = supervariable_starts(f, n);
  k.graph = compressed_graph(f, k.first, c);
  return k;
}

// The orderings of the compressed graph's vertices (new -> old); empty when CHOLMOD could not make
// one.
std::vector<int> nesdis_of(const Compressed& k, cholmod_common& c) {
  const std::size_t groups = k.first.size() - 1;
  // cholmod_nested_dissection reads its parameters from method[current].
  const int saved_current = c.current;
  c.current = 0;
  std::vector<int> group_perm(groups), cparent(groups), cmember(groups);
  const bool ok = cholmod_nested_dissection(k.graph, nullptr, 0, group_perm.data(), cparent.data(), cmember.data(), &c) >= 0;
  c.current = saved_current;
  c.status = CHOLMOD_OK;  // a failed ordering is not the caller's error: it orders without it
  return ok ? group_perm : std::vector<int>{};
}

std::vector<int> metis_of(const Compressed& k, cholmod_common& c) {
  std::vector<int> group_perm(k.first.size() - 1);
  // No postordering here: the analysis postorders whatever ordering it is given.
  const bool ok = cholmod_metis(k.graph, nullptr, 0, 0, group_perm.data(), &c) != 0;
  c.status = CHOLMOD_OK;
  return ok ? group_perm : std::vector<int>{};
}

}  // namespace

double factor_nonzeros(const cholmod_sparse& graph, const std::vector<int>& first, const std::vector<int>& group_perm) {
  const int n = static_cast<int>(graph.ncol);
  const int* gp = static_cast<const int*>(graph.p);
  const int* gi = static_cast<const int*>(graph.i);
  std::vector<int> position(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) position[group_perm[k]] = k;
  // Each vertex's earlier neighbours in the new order (the strictly upper part of its column of
  // the permuted graph), CSC by counting.
  std::vector<int> start(static_cast<std::size_t>(n) + 1, 0), earlier(static_cast<std::size_t>(gp[n]));
  for (int j = 0; j < n; ++j)
    for (int q = gp[j]; q < gp[j + 1]; ++q) ++start[std::max(position[j], position[gi[q]]) + 1];
  for (int k = 0; k < n; ++k) start[k + 1] += start[k];
  std::vector<int> next(start.begin(), start.end() - 1);
  for (int j = 0; j < n; ++j)
    for (int q = gp[j]; q < gp[j + 1]; ++q) {
      const int a = position[j], b = position[gi[q]];
      earlier[next[std::max(a, b)]++] = std::min(a, b);
    }
  auto width = [&](int k) { return static_cast<double>(first[group_perm[k] + 1] - first[group_perm[k]]); };
  // The elimination tree (Liu's algorithm with path compression through `ancestor`), then each row
  // subtree walked from the row's earlier neighbours up to the row: every vertex met has the row in
  // its column of the factor, and gains the row's width (`mark` stops a second visit).
  std::vector<int> parent(static_cast<std::size_t>(n), -1), ancestor(static_cast<std::size_t>(n), -1);
  for (int i = 0; i < n; ++i)
    for (int q = start[i]; q < start[i + 1]; ++q)
      for (int r = earlier[q]; r != i;) {
        const int up = ancestor[r];
        ancestor[r] = i;
        if (up == -1) {
          parent[r] = i;
          break;
        }
        r = up;
      }
  std::vector<double> below(static_cast<std::size_t>(n), 0.0);  // the width of a vertex's column of the factor
  std::vector<int> mark(static_cast<std::size_t>(n), -1);
  for (int i = 0; i < n; ++i) {
    mark[i] = i;
    for (int q = start[i]; q < start[i + 1]; ++q)
      for (int v = earlier[q]; mark[v] != i; v = parent[v]) {
        below[v] += width(i);
        mark[v] = i;
      }
  }
  double lnz = 0.0;
  for (int k = 0; k < n; ++k) {
    const double w = width(k);
    lnz += w * (w + 1.0) / 2.0 + w * below[k];
  }
  return lnz;
}

std::vector<int> nested_dissection_by_supervariables(const SparseMatrix& lower, cholmod_common& c) {
  Compressed k = compress(lower, c);
  if (!k.graph) return {};
  const std::vector<int> group_perm = nesdis_of(k, c);
  cholmod_free_sparse(&k.graph, &c);
  return group_perm.empty() ? std::vector<int>{} : expand(group_perm, k.first);
}

SupervariableOrderings orderings_by_supervariables(const SparseMatrix& lower, cholmod_common& c) {
  Compressed k = compress(lower, c);
  if (!k.graph) return {};
  SupervariableOrderings o;
  if (const std::vector<int> g = nesdis_of(k, c); !g.empty()) {
    o.lnz_nesdis = factor_nonzeros(*k.graph, k.first, g);
    o.nesdis = expand(g, k.first);
  }
  if (const std::vector<int> g = metis_of(k, c); !g.empty()) {
    o.lnz_metis = factor_nonzeros(*k.graph, k.first, g);
    o.metis = expand(g, k.first);
  }
  cholmod_free_sparse(&k.graph, &c);
  return o;
}

}  // namespace beamfea
