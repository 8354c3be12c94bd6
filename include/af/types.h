#pragma once
// The scalar type and the frame convention of the whole library, stated once.
//
// Scalar: af::Real is double. libccd (Debian's build) is double precision too, and the
// project's CMake refuses a libccd that is not.
//
// Frames follow Doom 3: right-handed, +Z up, +X forward, +Y left, lengths in the units of
// the file (Doom units, about an inch), angles in decls in degrees, angular velocities in
// rad/s. Time is in seconds.
//
// Rotations: inside the library a rotation matrix R maps body-local vectors to world vectors
// (column vectors, p_world = origin + R p_local); its columns are the body's local axes.
// Doom's "axis" matrices are the transpose (rows are the local axes, row vectors). Doom and
// md5 quaternions are conjugated with respect to the usual v' = q v q^-1 convention; the
// readers convert once at the boundary (see docs/conventions.md §0.2).

#include <array>

namespace af {

using Real = double;

// A plain triple for stages that know nothing of Eigen (text/): coordinates as written in a file.
using Real3 = std::array<Real, 3>;

}  // namespace af
