// Registration of the TAO types implemented in separate files (called by
// register_trust_region_tao_types()).
#pragma once

#include <petsctao.h>

#include "mlshell/objective.hpp"

namespace mlshell {

PetscErrorCode register_rmtr_tao_type();
/// Whether the last RMTR solve ended at the limiting accuracy.
bool rmtr_reached_limiting_accuracy(Tao tao);
/// The objective behind the finest level's callbacks (for its rounding-error estimate).
PetscErrorCode rmtr_set_error_source(Tao tao, Objective* source);
/// tao_projected_newton.cpp: the "pnewton" type's objective (step limits, rounding errors,
/// accepted iterates) and whether its last solve ended at the limiting accuracy.
PetscErrorCode projected_newton_set_source(Tao tao, Objective* source);
/// tao_newton_baselines.cpp: a direct solver for Newton directions, options prefix the Tao's
/// plus `prefix` (e.g. "tao_pnewton_"), KSPPREONLY with an LU factorisation by MUMPS.
PetscErrorCode create_direct_ksp(Tao tao, const char* prefix, KSP* ksp);
bool projected_newton_reached_limiting_accuracy(Tao tao);

/// Raises PETSC_ERR_ARG_WRONG unless `tao` is of the given type (for type-specific accessors).
inline PetscErrorCode require_tao_type(Tao tao, const char* type) {
  PetscBool same;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(tao), type, &same));
  PetscCheck(same, PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_WRONG, "not a %s solver", type);
  PetscFunctionReturn(0);
}

}  // namespace mlshell
