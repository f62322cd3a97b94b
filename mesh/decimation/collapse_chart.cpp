// The joint flattening of one edge collapse (collapse_chart.hpp).
//
// LSCM (Lévy, Petitjean, Ray, Maillot 2002): a map (u, v) of a triangle, linear on it, is
// conformal where the Cauchy–Riemann equations ∇v = R₉₀ ∇u hold, R₉₀ the rotation by +90° in the
// triangle's own counter-clockwise frame. With ∇φ_k = R₉₀ (p_{k+2} − p_{k+1}) / (2A) the
// gradients of the barycentric coordinates (p_k the corners in that frame, A the area), the
// conformal energy is
//   \f[ E = \sum_t A_t \big[ (\partial_x v + \partial_y u)^2 + (\partial_y v - \partial_x u)^2 \big], \f]
// two linear residuals per triangle, each weighted by √A_t. The energy does not depend on the
// frame chosen in each triangle (only on its orientation), and a similarity of the plane has zero
// energy, so a planar patch is laid out exactly up to the similarity the two pins fix.
#include "collapse_chart.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace mlshell {

namespace {

/// √A · ∇φ_k for k = 0, 1, 2 (columns) of the triangle (a, b, c) in its own frame, or false for
/// a triangle of zero area.
bool scaled_gradients(const Point3& a, const Point3& b, const Point3& c, Eigen::Matrix<double, 2, 3>* g) {
  const Point3 e1 = b - a, e2 = c - a;
  const double l1 = e1.norm();
  const Point3 n = e1.cross(e2);
  const double twice_area = n.norm();
  if (!(l1 > 0.0) || !(twice_area > 1e-14 * e1.squaredNorm() + 1e-300)) return false;
  const Point3 x = e1 / l1;
  const Point3 y = n.normalized().cross(x);
  const Eigen::Vector2d p[3] = {Eigen::Vector2d::Zero(), Eigen::Vector2d(l1, 0.0),
                                Eigen::Vector2d(e2.dot(x), e2.dot(y))};
  // √A ∇φ_k = R₉₀ (p_{k+2} − p_{k+1}) / (2√A).
  const double scale = 1.0 / (2.0 * std::sqrt(0.5 * twice_area));
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector2d e = p[(k + 2) % 3] - p[(k + 1) % 3];
    g->col(k) = scale * Eigen::Vector2d(-e.y(), e.x());
  }
  return true;
}

double signed_area(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
}

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

}  // namespace

void CollapseChart::collect_vertices() {
  const CollapseRecord& r = *record_;
  vertices_.clear();
  vertices_.push_back(r.removed);
  vertices_.push_back(r.kept);
  for (const Triangle& t : r.before)
    for (int v : t)
      if (std::find(vertices_.begin(), vertices_.end(), v) == vertices_.end()) vertices_.push_back(v);
  removed_local_ = 0;
  kept_local_ = 1;
}

int CollapseChart::local(int v) const {
  for (size_t k = 0; k < vertices_.size(); ++k)
    if (vertices_[k] == v) return static_cast<int>(k);
  throw std::logic_error("collapse chart: vertex " + std::to_string(v) +
                         " is not in the collapse's one-ring");
}

void CollapseChart::build() {
  lscm_before();
  bool ok = place_kept_lscm() && after_valid();
  if (!ok) {
    fell_back_ = true;
    ok = place_kept_in_kernel();
    if (!ok) tutte_chart();
  }
}

void CollapseChart::lscm_before() {
  const CollapseRecord& r = *record_;
  const int n = static_cast<int>(vertices_.size());
  // Unknowns (u_k, v_k) of the free vertices 2..n−1; removed and kept are pinned.
  const int free = 2 * (n - 2);
  before_.assign(n, Eigen::Vector2d::Zero());
  before_[kept_local_] = Eigen::Vector2d(1.0, 0.0);
  if (free == 0) return;
  Eigen::MatrixXd normal = Eigen::MatrixXd::Zero(free, free);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(free);
  Eigen::Matrix<double, 2, 3> g;
  for (const Triangle& t : r.before) {
    int c[3];
    for (int k = 0; k < 3; ++k) c[k] = local(t[k]);
    if (!scaled_gradients(before_3d_[c[0]], before_3d_[c[1]], before_3d_[c[2]], &g)) continue;
    // Residual 1: Σ g_x v + g_y u; residual 2: Σ g_y v − g_x u.
    for (int row = 0; row < 2; ++row) {
      double coef[6];  // (u, v) coefficients per corner
      double known = 0.0;
      for (int k = 0; k < 3; ++k) {
        coef[2 * k] = row == 0 ? g(1, k) : -g(0, k);
        coef[2 * k + 1] = row == 0 ? g(0, k) : g(1, k);
        if (c[k] < 2) known += coef[2 * k] * before_[c[k]].x() + coef[2 * k + 1] * before_[c[k]].y();
      }
      for (int a = 0; a < 6; ++a) {
        const int ia = 2 * (c[a / 2] - 2) + a % 2;
        if (c[a / 2] < 2) continue;
        rhs(ia) -= coef[a] * known;
        for (int b = 0; b < 6; ++b) {
          if (c[b / 2] < 2) continue;
          normal(ia, 2 * (c[b / 2] - 2) + b % 2) += coef[a] * coef[b];
        }
      }
    }
  }
  const Eigen::VectorXd x = normal.ldlt().solve(rhs);
  for (int k = 2; k < n; ++k) before_[k] = Eigen::Vector2d(x(2 * (k - 2)), x(2 * (k - 2) + 1));
}

bool CollapseChart::place_kept_lscm() {
  // Only the kept vertex is free: each after triangle's two residual rows have coefficients
  // (g_y, g_x) and (−g_x, g_y) on (u, v), orthogonal and of equal length, so the normal matrix is
  // Σ |√A ∇φ_kept|² times the identity.
  const CollapseRecord& r = *record_;
  double diagonal = 0.0;
  Eigen::Vector2d rhs = Eigen::Vector2d::Zero();
  Eigen::Matrix<double, 2, 3> g;
  for (const Triangle& t : r.after) {
    Point3 x[3];
    int kept_corner = -1;
    for (int k = 0; k < 3; ++k) {
      if (t[k] == r.kept) {
        kept_corner = k;
        x[k] = r.placement;
      } else {
        x[k] = before_3d_[local(t[k])];
      }
    }
    if (kept_corner < 0 || !scaled_gradients(x[0], x[1], x[2], &g)) continue;
    double known[2] = {0.0, 0.0};
    for (int k = 0; k < 3; ++k) {
      if (k == kept_corner) continue;
      const Eigen::Vector2d& q = before_[local(t[k])];
      known[0] += g(1, k) * q.x() + g(0, k) * q.y();
      known[1] += -g(0, k) * q.x() + g(1, k) * q.y();
    }
    const double gx = g(0, kept_corner), gy = g(1, kept_corner);
    diagonal += gx * gx + gy * gy;
    rhs.x() -= gy * known[0] - gx * known[1];
    rhs.y() -= gx * known[0] + gy * known[1];
  }
  if (!(diagonal > 0.0)) return false;
  kept_after_ = rhs / diagonal;
  return kept_after_.allFinite() &&
         std::all_of(before_.begin(), before_.end(), [](const auto& p) { return p.allFinite(); });
}

bool CollapseChart::after_valid() const {
  const CollapseRecord& r = *record_;
  double size = 0.0;
  for (const auto& p : before_) size = std::max(size, (p - kept_after_).squaredNorm());
  for (const Triangle& t : r.after) {
    Eigen::Vector2d q[3];
    for (int k = 0; k < 3; ++k) q[k] = t[k] == r.kept ? kept_after_ : before_[local(t[k])];
    if (!(signed_area(q[0], q[1], q[2]) > 1e-12 * size)) return false;
  }
  return true;
}

bool CollapseChart::place_kept_in_kernel() {
  // The kept vertex sees each after triangle (kept, a, b) counter-clockwise where it lies left
  // of a → b: clip a box around the chart by these half-planes (Sutherland–Hodgman) and take
  // the clipped polygon's centroid.
  const CollapseRecord& r = *record_;
  Eigen::Vector2d lo = before_[0], hi = before_[0];
  for (const auto& p : before_) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Eigen::Vector2d margin = Eigen::Vector2d::Constant((hi - lo).maxCoeff());
  lo -= margin;
  hi += margin;
  std::vector<Eigen::Vector2d> poly = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}}, next;
  for (const Triangle& t : r.after) {
    int k = 0;
    while (k < 3 && t[k] != r.kept) ++k;
    if (k == 3) continue;
    const Eigen::Vector2d a = before_[local(t[(k + 1) % 3])], b = before_[local(t[(k + 2) % 3])];
    const auto side = [&](const Eigen::Vector2d& q) { return cross(b - a, q - a); };
    next.clear();
    for (size_t i = 0; i < poly.size(); ++i) {
      const Eigen::Vector2d& p = poly[i];
      const Eigen::Vector2d& q = poly[(i + 1) % poly.size()];
      const double sp = side(p), sq = side(q);
      if (sp >= 0.0) next.push_back(p);
      if ((sp >= 0.0) != (sq >= 0.0)) next.push_back(p + (sp / (sp - sq)) * (q - p));
    }
    poly.swap(next);
    if (poly.size() < 3) return false;
  }
  double area = 0.0;
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (size_t i = 0; i < poly.size(); ++i) {
    const double w = cross(poly[i], poly[(i + 1) % poly.size()]);
    area += w;
    centroid += w * (poly[i] + poly[(i + 1) % poly.size()]);
  }
  if (!(area > 1e-14 * (hi - lo).squaredNorm())) return false;
  kept_after_ = centroid / (3.0 * area);
  return after_valid();
}

bool CollapseChart::tutte_chart() {
  // A closed link (an interior edge): its vertices in their cyclic order on the unit circle,
  // removed and kept at the uniform average of their neighbours before the collapse, kept at the
  // average of the link after it (a convex polygon is seen counter-clockwise from inside).
  const CollapseRecord& r = *record_;
  const int n = static_cast<int>(vertices_.size());
  std::vector<int> next(n, -1);
  for (const Triangle& t : r.after) {
    int k = 0;
    while (k < 3 && t[k] != r.kept) ++k;
    if (k == 3) return false;
    const int a = local(t[(k + 1) % 3]);
    if (next[a] >= 0) return false;
    next[a] = local(t[(k + 2) % 3]);
  }
  const int m = n - 2;
  if (m < 3 || static_cast<int>(r.after.size()) != m) return false;
  std::vector<int> cycle = {2};
  while (static_cast<int>(cycle.size()) < m) {
    const int v = next[cycle.back()];
    if (v < 2 || v == cycle.front()) return false;
    cycle.push_back(v);
  }
  if (next[cycle.back()] != cycle.front()) return false;
  for (int i = 0; i < m; ++i) {
    const double angle = 2.0 * std::numbers::pi * i / m;
    before_[cycle[i]] = Eigen::Vector2d(std::cos(angle), std::sin(angle));
  }
  // deg_r x_r − a x_k = Σ link neighbours of r, deg_k x_k − a x_r = Σ link neighbours of k.
  std::vector<std::vector<int>> neighbours(2);
  for (const Triangle& t : r.before)
    for (int k = 0; k < 3; ++k) {
      const int c = local(t[k]);
      if (c > 1) continue;
      for (int j = 1; j < 3; ++j) {
        const int o = local(t[(k + j) % 3]);
        auto& list = neighbours[c];
        if (std::find(list.begin(), list.end(), o) == list.end()) list.push_back(o);
      }
    }
  Eigen::Matrix2d a = Eigen::Matrix2d::Zero();
  Eigen::Matrix<double, 2, 2> b = Eigen::Matrix<double, 2, 2>::Zero();  // rows: r, k; cols: x, y
  for (int c = 0; c < 2; ++c) {
    a(c, c) = static_cast<double>(neighbours[c].size());
    for (int o : neighbours[c]) {
      if (o < 2)
        a(c, o) -= 1.0;
      else
        b.row(c) += before_[o].transpose();
    }
  }
  const Eigen::Matrix2d x = a.fullPivLu().solve(b);
  before_[removed_local_] = x.row(0).transpose();
  before_[kept_local_] = x.row(1).transpose();
  kept_after_ = Eigen::Vector2d::Zero();
  for (int i = 0; i < m; ++i) kept_after_ += before_[cycle[i]] / m;
  return true;
}

Eigen::Vector2d CollapseChart::before_position(const Triangle& corners,
                                               const Eigen::Vector3d& weights) const {
  Eigen::Vector2d p = Eigen::Vector2d::Zero();
  for (int k = 0; k < 3; ++k) p += weights[k] * before_[local(corners[k])];
  return p;
}

int CollapseChart::locate(const Eigen::Vector2d& p, Eigen::Vector3d* weights, double* snap) const {
  const CollapseRecord& r = *record_;
  int best = -1;
  double best_min = -std::numeric_limits<double>::infinity();
  Eigen::Vector3d best_w = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < r.after.size(); ++i) {
    const Triangle& t = r.after[i];
    Eigen::Vector2d q[3];
    for (int k = 0; k < 3; ++k) q[k] = t[k] == r.kept ? kept_after_ : before_[local(t[k])];
    const double area = signed_area(q[0], q[1], q[2]);
    if (!(area > 0.0)) continue;  // a folded or degenerate triangle contains nothing
    Eigen::Vector3d w(signed_area(p, q[1], q[2]), signed_area(q[0], p, q[2]),
                      signed_area(q[0], q[1], p));
    w /= area;
    if (w.minCoeff() > best_min) {
      best_min = w.minCoeff();
      best = static_cast<int>(i);
      best_w = w;
    }
  }
  if (best < 0) {
    // Every after triangle is folded or flat in the chart: the first one, at its centroid.
    *weights = Eigen::Vector3d::Constant(1.0 / 3.0);
    *snap = 1.0;
    return 0;
  }
  *snap = std::max(0.0, -best_min);
  best_w = best_w.cwiseMax(0.0);
  *weights = best_w / best_w.sum();
  return best;
}

}  // namespace mlshell
