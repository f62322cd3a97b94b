// The distributed shell prolongation (ShellTransfer) against the serial kernel, on whatever
// ranks PETSC_COMM_WORLD has (ShellTransfer.*), and on two (MpiShellTransfer.*, ctest
// mpi.two_ranks): prolong equals ShellProlongation::apply; restriction is the exact transpose of
// the direction, which is the derivative of prolong; the coarse operator is J_Pᵀ A J_P, also
// refilled for a new x₀; the correction vanishes at its start; the natural projection recovers
// rest states, and its misfit on a deformed state is the survivors' rest move turned.
#include <gtest/gtest.h>
#include <petscmat.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <memory>

#include "mlshell/prolongation/triangle_transfer.hpp"
#include "mlshell/triangle/triangle_discretization.hpp"
#include "physics_fixtures.hpp"
#include "prolongation/prolongation_fixtures.hpp"

using namespace mlshell;

namespace {

/// Two triangle levels on PETSC_COMM_WORLD (each partitioned by METIS on its own, so fine
/// vertices read coarse vertices of other ranks) and the transfer between them.
struct TwoLevels {
  RefinedPair pair;
  std::unique_ptr<TriangleDiscretization> coarse_disc, fine_disc;
  std::unique_ptr<ParallelLayout> coarse, fine;
  std::shared_ptr<const ShellProlongation> kernel;
  std::unique_ptr<ShellTransfer> transfer;
  explicit TwoLevels(RefinedPair p) : pair(std::move(p)) {
    coarse_disc = std::make_unique<TriangleDiscretization>(pair.coarse);
    fine_disc = std::make_unique<TriangleDiscretization>(pair.fine);
    coarse = std::make_unique<ParallelLayout>(PETSC_COMM_WORLD, *coarse_disc);
    fine = std::make_unique<ParallelLayout>(PETSC_COMM_WORLD, *fine_disc);
    kernel = std::make_shared<ShellProlongation>(make_prolongation(pair));
    transfer = std::make_unique<ShellTransfer>(*coarse, *fine, kernel, 0.25, pair.coarse_to_fine);
  }
  int nc() const { return pair.coarse.num_points(); }
  int nf() const { return pair.fine.num_points(); }
  /// A global vector from natural-order values (the same on every rank).
  Vec coarse_vector(const std::vector<double>& natural) const { return make(*coarse, natural); }
  Vec fine_vector(const std::vector<double>& natural) const { return make(*fine, natural); }
  /// Natural-order values on every rank.
  std::vector<double> coarse_natural(Vec v) const { return read(*coarse, v, 3 * nc()); }
  std::vector<double> fine_natural(Vec v) const { return read(*fine, v, 3 * nf()); }

  static Vec make(const ParallelLayout& layout, const std::vector<double>& natural) {
    Vec v;
    layout.create_vector(&v);
    layout.scatter_natural(layout.rank() == 0 ? natural : std::vector<double>{}, v);
    return v;
  }
  static std::vector<double> read(const ParallelLayout& layout, Vec v, int n) {
    std::vector<double> natural;
    layout.gather_natural(v, natural);
    natural.resize(n);
    MPI_Bcast(natural.data(), n, MPI_DOUBLE, 0, layout.comm());
    return natural;
  }
};

std::vector<double> wave(int n, double amplitude, double phase) {
  std::vector<double> v(n);
  for (int i = 0; i < n; ++i) v[i] = amplitude * std::sin(0.37 * i + phase) * std::cos(0.11 * i);
  return v;
}

std::vector<Point3> positions(const std::vector<Point3>& rest, const std::vector<double>& u) {
  std::vector<Point3> x = rest;
  for (size_t i = 0; i < x.size(); ++i) x[i] += Point3(u[3 * i], u[3 * i + 1], u[3 * i + 2]);
  return x;
}

double dot(Vec a, Vec b) {
  PetscScalar d;
  VecDot(a, b, &d);
  return d;
}

double norm(Vec a) {
  PetscReal n;
  VecNorm(a, NORM_INFINITY, &n);
  return n;
}

void destroy(std::initializer_list<Vec*> vectors) {
  for (Vec* v : vectors) VecDestroy(v);
}

void check_prolong_matches_the_kernel() {
  TwoLevels t(with_fine_numbering_reversed(sphere_pair(2, true)));
  const std::vector<double> uc = wave(3 * t.nc(), 0.1, 0.3);
  Vec c = t.coarse_vector(uc), f, zero;
  t.fine->create_vector(&f);
  ASSERT_EQ(t.transfer->prolong(c, f), 0);
  const std::vector<Point3> image = t.kernel->apply(positions(t.pair.coarse.points, uc));
  const std::vector<Point3> rest_image = t.kernel->apply(t.pair.coarse.points);
  std::vector<double> expected(3 * t.nf());
  for (int i = 0; i < t.nf(); ++i)
    for (int k = 0; k < 3; ++k) expected[3 * i + k] = image[i][k] - rest_image[i][k];
  EXPECT_LT(relative_difference(t.fine_natural(f), expected), 1e-13);
  // u_c = 0 prolongs to exactly 0.
  t.coarse->create_vector(&zero);
  ASSERT_EQ(t.transfer->prolong(zero, f), 0);
  EXPECT_EQ(norm(f), 0.0);
  EXPECT_EQ(t.transfer->relative_cost(), 0.25);
  destroy({&c, &f, &zero});
}

void check_restriction_is_the_transpose() {
  TwoLevels t(wavy_plate_pair(0.1));
  Vec x0 = t.coarse_vector(wave(3 * t.nc(), 0.05, 0.1)),
      d = t.coarse_vector(wave(3 * t.nc(), 1.0, 2.0));
  Vec g = t.fine_vector(wave(3 * t.nf(), 1.0, 0.7)), Jd, Jtg;
  t.fine->create_vector(&Jd);
  t.coarse->create_vector(&Jtg);
  VecSet(Jtg, 5.0);  // restrict_gradient overwrites
  ASSERT_EQ(t.transfer->prolong_direction(x0, d, Jd), 0);
  ASSERT_EQ(t.transfer->restrict_gradient(x0, g, Jtg), 0);
  const double a = dot(Jd, g), b = dot(d, Jtg);
  EXPECT_NEAR(a, b, 1e-13 * std::abs(a));
  // J d is the derivative of prolong at x₀ (central differences).
  const double h = 1e-6;
  Vec plus, minus, fp, fm;
  VecDuplicate(x0, &plus);
  VecDuplicate(x0, &minus);
  VecWAXPY(plus, h, d, x0);
  VecWAXPY(minus, -h, d, x0);
  t.fine->create_vector(&fp);
  t.fine->create_vector(&fm);
  t.transfer->prolong(plus, fp);
  t.transfer->prolong(minus, fm);
  VecAXPY(fp, -1.0, fm);
  VecScale(fp, 1.0 / (2.0 * h));
  VecAXPY(fp, -1.0, Jd);
  EXPECT_LT(norm(fp), 1e-7 * norm(Jd));
  // The assembled J_P is the same operator.
  Mat J;
  ASSERT_EQ(t.transfer->jacobian_matrix(x0, &J), 0);
  MatMult(J, d, fm);
  VecAXPY(fm, -1.0, Jd);
  EXPECT_LT(norm(fm), 1e-14 * norm(Jd));
  destroy({&x0, &d, &g, &Jd, &Jtg, &plus, &minus, &fp, &fm});
}

/// A symmetric fine matrix with the fine level's pattern: 2 I on the diagonal, c_ab I between
/// the corners of each triangle (added once per triangle side met).
Mat fine_matrix(const TwoLevels& t) {
  Mat A;
  t.fine->create_matrix(&A);
  for (int f : t.fine->local_elements()) {
    const Triangle& tri = t.pair.fine.triangles[f];
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 3; ++l) {
        const int a = tri[k], b = tri[l];
        const double v = a == b ? 2.0 / 6.0 : 0.05 * (1.0 + std::sin(0.3 * (a + b)));
        PetscScalar block[9] = {v, 0, 0, 0, v, 0, 0, 0, v};
        const PetscInt row = t.fine->petsc_of(a), col = t.fine->petsc_of(b);
        MatSetValuesBlocked(A, 1, &row, 1, &col, block, ADD_VALUES);
      }
  }
  MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY);
  return A;
}

/// max |A_c v − Jᵀ A J v| / max |A_c v| for a random v.
double galerkin_error(const TwoLevels& t, Vec x0, Mat A, Mat Ac) {
  Vec v = t.coarse_vector(wave(3 * t.nc(), 1.0, 1.3)), Jv, AJv, JtAJv, Acv;
  t.fine->create_vector(&Jv);
  t.fine->create_vector(&AJv);
  t.coarse->create_vector(&JtAJv);
  t.coarse->create_vector(&Acv);
  t.transfer->prolong_direction(x0, v, Jv);
  MatMult(A, Jv, AJv);
  t.transfer->restrict_gradient(x0, AJv, JtAJv);
  MatMult(Ac, v, Acv);
  VecAXPY(JtAJv, -1.0, Acv);
  const double e = norm(JtAJv) / norm(Acv);
  destroy({&v, &Jv, &AJv, &JtAJv, &Acv});
  return e;
}

void check_coarse_operator_is_galerkin() {
  TwoLevels t(sphere_pair(2, true));
  Mat A = fine_matrix(t), Ac = nullptr;
  Vec x0 = t.coarse_vector(wave(3 * t.nc(), 0.1, 0.5));
  ASSERT_EQ(t.transfer->coarse_operator(x0, A, MAT_INITIAL_MATRIX, &Ac), 0);
  EXPECT_LT(galerkin_error(t, x0, A, Ac), 1e-13);
  // Another start, the same pattern: refilled in place.
  Vec x1 = t.coarse_vector(wave(3 * t.nc(), 0.2, 2.5));
  Mat before = Ac;
  ASSERT_EQ(t.transfer->coarse_operator(x1, A, MAT_REUSE_MATRIX, &Ac), 0);
  EXPECT_EQ(Ac, before);
  EXPECT_LT(galerkin_error(t, x1, A, Ac), 1e-13);
  EXPECT_GT(galerkin_error(t, x0, A, Ac), 1e-6);  // it did change
  MatDestroy(&Ac);
  MatDestroy(&A);
  destroy({&x0, &x1});
}

void check_correction_vanishes_at_the_start() {
  TwoLevels t(dome_pair());
  Vec x0 = t.coarse_vector(wave(3 * t.nc(), 0.1, 0.2)),
      x = t.coarse_vector(wave(3 * t.nc(), 0.1, 1.9));
  Vec s, p, p0;
  t.fine->create_vector(&s);
  t.fine->create_vector(&p);
  t.fine->create_vector(&p0);
  ASSERT_EQ(t.transfer->prolong_correction(x0, x0, s), 0);
  EXPECT_EQ(norm(s), 0.0);
  ASSERT_EQ(t.transfer->prolong_correction(x0, x, s), 0);
  t.transfer->prolong(x, p);
  t.transfer->prolong(x0, p0);
  VecAXPY(p, -1.0, p0);
  VecAXPY(p, -1.0, s);
  EXPECT_LT(norm(p), 1e-14 * norm(s));
  destroy({&x0, &x, &s, &p, &p0});
}

void check_projection() {
  for (const bool moved : {false, true}) {
    TwoLevels t(with_fine_numbering_reversed(sphere_pair(2, moved)));
    Vec uc, f, back;
    t.coarse->create_vector(&uc);
    t.coarse->create_vector(&back);
    t.fine->create_vector(&f);
    // Rest: Π(P(x̄_c)) = x̄_c, i.e. Π(prolong(0)) = 0, exactly.
    t.transfer->prolong(uc, f);
    VecSet(back, 1.0);
    ASSERT_EQ(t.transfer->project(f, back), 0);
    EXPECT_EQ(norm(back), 0.0);
    // A deformed state: the coarse shape turned by 0.3 rad and stretched by 5 % along z.
    const Eigen::Matrix3d Q =
        Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 2).normalized()).toRotationMatrix() *
        Eigen::Vector3d(1.0, 1.0, 1.05).asDiagonal();
    std::vector<double> u(3 * t.nc());
    for (int k = 0; k < t.nc(); ++k) {
      const Point3& X = t.pair.coarse.points[k];
      const Point3 d = Q * X - X;
      for (int c = 0; c < 3; ++c) u[3 * k + c] = d[c];
    }
    VecDestroy(&uc);
    uc = t.coarse_vector(u);
    t.transfer->prolong(uc, f);
    t.transfer->project(f, back);
    VecAXPY(back, -1.0, uc);
    const double misfit = norm(back) / norm(uc);
    if (t.coarse->rank() == 0)
      std::printf(
          "[ShellTransfer] projection misfit |Π(P(x_c)) − x_c|/|u_c| = %.3g (survivors %s)\n",
          misfit, moved ? "moved 2 %" : "kept their rest place");
    if (moved) {
      EXPECT_GT(misfit, 1e-4);  // the survivors' 2 % rest move, turned by 0.3 rad
      EXPECT_LT(misfit, 0.05);
    } else {
      EXPECT_LT(misfit, 1e-14);
    }
    // Only the natural projection is offered.
    PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
    EXPECT_EQ(t.transfer->project(f, back, LevelTransfer::Projection::kLeastSquares),
              PETSC_ERR_SUP);
    EXPECT_EQ(t.transfer->project(f, back, LevelTransfer::Projection::kScaledRestriction),
              PETSC_ERR_SUP);
    PetscPopErrorHandler();
    destroy({&uc, &f, &back});
  }
}

void check_rejects_mismatched_levels() {
  const RefinedPair pair = sphere_pair(1);
  TriangleDiscretization coarse_disc(pair.coarse), fine_disc(pair.fine);
  ParallelLayout coarse(PETSC_COMM_WORLD, coarse_disc), fine(PETSC_COMM_WORLD, fine_disc);
  auto kernel = std::make_shared<ShellProlongation>(make_prolongation(pair));
  // Columns beyond a smaller coarse level (the icosahedron's 12 points), then rows that differ.
  TriangleDiscretization small_disc(make_sphere(1.0, 0));
  ParallelLayout small(PETSC_COMM_WORLD, small_disc);
  EXPECT_THROW(ShellTransfer(small, fine, kernel, 0.25), std::invalid_argument);
  EXPECT_THROW(ShellTransfer(coarse, coarse, kernel, 0.25), std::invalid_argument);
  std::vector<int> short_map(pair.coarse_to_fine.begin(), pair.coarse_to_fine.end() - 1);
  EXPECT_THROW(ShellTransfer(coarse, fine, kernel, 0.25, short_map), std::invalid_argument);
  ShellTransfer without(coarse, fine, kernel, 0.25);
  Vec f, c;
  fine.create_vector(&f);
  coarse.create_vector(&c);
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
  EXPECT_EQ(without.project(f, c), PETSC_ERR_SUP);
  PetscPopErrorHandler();
  destroy({&f, &c});
}

int world_size() {
  int size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  return size;
}

}  // namespace

TEST(ShellTransfer, ProlongMatchesTheKernel) { check_prolong_matches_the_kernel(); }
TEST(ShellTransfer, RestrictionIsTheTransposeOfTheDirection) {
  check_restriction_is_the_transpose();
}
TEST(ShellTransfer, CoarseOperatorIsGalerkin) { check_coarse_operator_is_galerkin(); }
TEST(ShellTransfer, CorrectionVanishesAtItsStart) { check_correction_vanishes_at_the_start(); }
TEST(ShellTransfer, NaturalProjectionRecoversRestStates) { check_projection(); }
TEST(ShellTransfer, RejectsMismatchedLevels) { check_rejects_mismatched_levels(); }

TEST(MpiShellTransfer, AgreesWithTheSerialKernelOnTwoRanks) {
  ASSERT_GE(world_size(), 2) << "run under mpiexec -n 2";
  {  // the levels really are split, and fine vertices read coarse vertices of the other rank
    TwoLevels t(sphere_pair(2, true));
    ASSERT_GT(t.fine->num_owned_points(), 0);
    ASSERT_LT(t.fine->num_owned_points(), t.nf());
    int remote = 0;
    const int first = t.coarse->first_owned(), last = first + t.coarse->num_owned_points();
    for (int j = 0; j < t.fine->num_owned_points(); ++j)
      for (int c : t.kernel->columns(t.fine->local_points()[j]))
        remote += t.coarse->petsc_of(c) < first || t.coarse->petsc_of(c) >= last;
    int any = 0;
    MPI_Allreduce(&remote, &any, 1, MPI_INT, MPI_SUM, PETSC_COMM_WORLD);
    EXPECT_GT(any, 0);
  }
  check_prolong_matches_the_kernel();
  check_restriction_is_the_transpose();
  check_coarse_operator_is_galerkin();
  check_correction_vanishes_at_the_start();
  check_projection();
  check_rejects_mismatched_levels();
}
