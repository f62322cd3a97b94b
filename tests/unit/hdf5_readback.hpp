// Datasets of an HDF5 result file read back through PETSc's HDF5 viewer (for the output tests).
#pragma once

#include <gtest/gtest.h>
#include <petscis.h>
#include <petscvec.h>
#include <petscviewer.h>

#include <cstdint>
#include <filesystem>
#include <vector>

namespace mlshell_test {

/// PETSc's HDF5 viewer reading `h5` on this process.
inline PetscViewer open_reader(const std::filesystem::path& h5) {
  PetscViewer v = nullptr;
  EXPECT_EQ(PetscViewerCreate(PETSC_COMM_SELF, &v), 0);
  EXPECT_EQ(PetscViewerSetType(v, PETSCVIEWERHDF5), 0);
  EXPECT_EQ(PetscViewerFileSetMode(v, FILE_MODE_READ), 0);
  EXPECT_EQ(PetscViewerFileSetName(v, h5.c_str()), 0);
  return v;
}

// Reads a Vec dataset back through PETSc's HDF5 viewer; returns its values and block size.
inline std::vector<double> load_vec(const std::filesystem::path& h5, const char* name,
                                    PetscInt* bs) {
  PetscViewer v = open_reader(h5);
  Vec x = nullptr;
  EXPECT_EQ(VecCreate(PETSC_COMM_SELF, &x), 0);
  EXPECT_EQ(PetscObjectSetName(reinterpret_cast<PetscObject>(x), name), 0);
  std::vector<double> out;
  if (VecLoad(x, v) == 0) {
    PetscInt n = 0;
    const PetscScalar* a = nullptr;
    VecGetSize(x, &n);
    VecGetBlockSize(x, bs);
    VecGetArrayRead(x, &a);
    out.assign(a, a + n);
    VecRestoreArrayRead(x, &a);
  } else {
    ADD_FAILURE() << "VecLoad of " << name << " from " << h5 << " failed";
  }
  VecDestroy(&x);
  PetscViewerDestroy(&v);
  return out;
}

inline std::vector<std::int64_t> load_is(const std::filesystem::path& h5, const char* name,
                                         PetscInt* bs) {
  PetscViewer v = open_reader(h5);
  IS is = nullptr;
  EXPECT_EQ(ISCreate(PETSC_COMM_SELF, &is), 0);
  EXPECT_EQ(ISSetType(is, ISGENERAL), 0);
  EXPECT_EQ(PetscObjectSetName(reinterpret_cast<PetscObject>(is), name), 0);
  std::vector<std::int64_t> out;
  if (ISLoad(is, v) == 0) {
    PetscInt n = 0;
    const PetscInt* idx = nullptr;
    ISGetLocalSize(is, &n);
    ISGetBlockSize(is, bs);
    ISGetIndices(is, &idx);
    out.assign(idx, idx + n);
    ISRestoreIndices(is, &idx);
  } else {
    ADD_FAILURE() << "ISLoad of " << name << " from " << h5 << " failed";
  }
  ISDestroy(&is);
  PetscViewerDestroy(&v);
  return out;
}

}  // namespace mlshell_test
