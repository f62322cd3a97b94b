// Frames written in parallel (every rank its slice, DistributedSampling + XdmfSeries and the
// OBJ writer on the world communicator) hold the datasets a serial writer gives for the same
// displacements.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "hdf5_readback.hpp"
#include "mlshell/distributed_sampling.hpp"
#include "mlshell/output_files.hpp"
#include "physics_fixtures.hpp"

using namespace mlshell;
using mlshell_test::load_is;
using mlshell_test::load_vec;

namespace {

double max_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0;
  for (size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
  return d;
}

}  // namespace

TEST(MpiParallelOutput, FramesOnTwoRanksHoldTheSerialDatasets) {
  int size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  ASSERT_GE(size, 2) << "run under mpiexec -n 2";
  TestProblem tp("all", PETSC_COMM_WORLD);
  const auto sampling = tp.disc->sampling(3);
  Vec u;
  tp.layout->create_vector(&u);
  tp.random_state(u, 1e-2, 5);
  std::vector<double> natural;
  tp.layout->gather_natural(u, natural);
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "mlshell_parallel_output_test";
  if (tp.layout->rank() == 0) std::filesystem::remove_all(dir);

  // Parallel: each rank its slice, plus a cell field held by rank 0 alone (as face fields are).
  FrameData frame;
  // Each rank samples its own part (SubdivisionDiscretization::sampling_part).
  DistributedSampling distributed(*tp.disc->sampling_part(3, tp.layout->rank(), size),
                                  *tp.layout);
  ASSERT_EQ(distributed.sample(u, &frame.geometry, &frame.displacement), 0);
  ASSERT_EQ(distributed.topology(&frame.topology), 0);
  PetscInt local_points;
  VecGetLocalSize(frame.geometry, &local_points);
  EXPECT_GT(local_points, 0) << "a rank writes nothing: the test checks no parallel write";
  std::vector<double> field(tp.layout->rank() == 0 ? sampling->num_cells() : 0);
  for (size_t i = 0; i < field.size(); ++i) field[i] = 0.5 * static_cast<double>(i);
  Vec field_vec;
  VecCreateMPIWithArray(PETSC_COMM_WORLD, 1, static_cast<PetscInt>(field.size()), PETSC_DETERMINE,
                        field.data(), &field_vec);
  PetscObjectSetName((PetscObject)field_vec, "cell_strain");
  frame.cell_fields.emplace_back("strain", field_vec);
  XdmfSeries parallel(dir / "parallel", "shell", PETSC_COMM_WORLD);
  parallel.add_frame(3, 0.5, frame);
  const std::string comment = "mlshell test\nsecond line";
  write_obj(PETSC_COMM_WORLD, dir / "parallel" / "shell.obj", frame, comment);
  VecDestroy(&frame.geometry);
  VecDestroy(&frame.displacement);
  ISDestroy(&frame.topology);
  VecDestroy(&field_vec);

  if (tp.layout->rank() == 0) {
    SurfaceSample serial = sampling->sample(natural);
    serial.cell_data.emplace_back("strain", field);
    XdmfSeries one(dir / "serial", "shell");
    one.add_frame(3, 0.5, serial);
    const auto a = dir / "parallel" / "shell_000003.h5", b = dir / "serial" / "shell_000003.h5";
    PetscInt bs_a, bs_b;
    const auto ga = load_vec(a, "geometry", &bs_a), gb = load_vec(b, "geometry", &bs_b);
    ASSERT_EQ(ga.size(), gb.size());
    EXPECT_EQ(bs_a, 3);
    EXPECT_EQ(bs_b, 3);
    double extent = 0.0;
    for (double x : gb) extent = std::max(extent, std::abs(x));
    // W u sums its terms in another order on two ranks: equal to round-off, not bit for bit.
    EXPECT_LT(max_difference(ga, gb), 1e-14 * extent);
    const auto da = load_vec(a, "displacement", &bs_a), db = load_vec(b, "displacement", &bs_b);
    ASSERT_EQ(da.size(), db.size());
    EXPECT_LT(max_difference(da, db), 1e-13 * 1e-2);
    EXPECT_EQ(load_is(a, "topology", &bs_a), load_is(b, "topology", &bs_b));
    EXPECT_EQ(bs_a, 4);
    EXPECT_EQ(load_vec(a, "cell_strain", &bs_a), field);
    std::ifstream xa(dir / "parallel" / "shell.xdmf"), xb(dir / "serial" / "shell.xdmf");
    std::stringstream ta, tb;
    ta << xa.rdbuf();
    tb << xb.rdbuf();
    EXPECT_EQ(ta.str(), tb.str());
    // The OBJ text: the same lines, coordinates equal to round-off.
    write_obj(dir / "serial" / "shell.obj", serial, comment);
    std::ifstream oa(dir / "parallel" / "shell.obj"), ob(dir / "serial" / "shell.obj");
    std::string la, lb;
    size_t lines = 0, vertices = 0, faces = 0;
    while (std::getline(ob, lb)) {
      if (!std::getline(oa, la)) {
        ADD_FAILURE() << "the parallel OBJ ends at line " << lines;
        break;
      }
      ++lines;
      if (lb.rfind("v ", 0) == 0) {
        ++vertices;
        std::istringstream sa(la.substr(1)), sb(lb.substr(1));
        EXPECT_EQ(la.substr(0, 2), "v ") << "line " << lines;
        for (int c = 0; c < 3; ++c) {
          double xa, xb;
          sa >> xa;
          sb >> xb;
          EXPECT_LE(std::abs(xa - xb), 1e-14 * extent) << "line " << lines;
        }
      } else {
        faces += lb.rfind("f ", 0) == 0;
        EXPECT_EQ(la, lb) << "line " << lines;
      }
    }
    EXPECT_FALSE(std::getline(oa, la)) << "the parallel OBJ has more lines";
    EXPECT_EQ(vertices, serial.points.size() / 3);
    EXPECT_EQ(faces, static_cast<size_t>(serial.num_cells()));
    std::filesystem::remove_all(dir);
  }
  VecDestroy(&u);
}
