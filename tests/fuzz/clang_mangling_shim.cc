// Part of libestep in ESTEP_BUILD_FUZZERS builds only (CMakeLists.txt), which
// compile estep with clang against Debian's deal.II, compiled with GCC. The two
// compilers mangle one function that estep uses differently:
// TrilinosWrappers::SparseMatrix::vmult<Vector<double>>, whose return type is
// an enable_if of std::is_same (GCC abbreviates std:: in it, clang 14 does
// not). The CG solve of the implicit integrators (shifted_stiffness_solver.cc)
// calls it under clang's name; this definition of that name forwards to
// deal.II's (the same member function: the matrix is the first argument).
#include <deal.II/lac/vector.h>

namespace dealii
{
  namespace TrilinosWrappers
  {
    class SparseMatrix;
  }
} // namespace dealii

using Matrix = dealii::TrilinosWrappers::SparseMatrix;
using Vector = dealii::Vector<double>;

extern "C" void
deal_ii_vmult(const Matrix *, Vector &, const Vector &) __asm__(
  "_ZNK6dealii16TrilinosWrappers12SparseMatrix5vmultINS_6VectorIdEEEENSt9enable_"
  "ifIXsrSt7is_sameINT_10value_typeEdE5valueEvE4typeERS7_RKS7_");

extern "C" void
clang_vmult(const Matrix *matrix, Vector &dst, const Vector &src) __asm__(
  "_ZNK6dealii16TrilinosWrappers12SparseMatrix5vmultINS_6VectorIdEEEENSt9enable_"
  "ifIXsr3std7is_sameINT_10value_typeEdEE5valueEvE4typeERS6_RKS6_");

void
clang_vmult(const Matrix *matrix, Vector &dst, const Vector &src)
{
  deal_ii_vmult(matrix, dst, src);
}
