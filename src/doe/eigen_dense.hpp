#pragma once
// Eigen's dense module for the fits and solves of src/doe. GCC 12 reports a false
// -Wmaybe-uninitialized inside its own AVX-512 intrinsics when Eigen is inlined with
// -march=native (GCC bug 105593; thermal/static_bed_solver.cpp does the same for the
// sparse modules): the warning is about Eigen's headers, not about our code.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <Eigen/Dense>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
