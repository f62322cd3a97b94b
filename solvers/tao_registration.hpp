// Registration of the TAO types implemented in separate files (called by
// register_trust_region_tao_types()).
#pragma once

#include <petsctao.h>

namespace mlshell {

PetscErrorCode register_rmtr_tao_type();

}  // namespace mlshell
