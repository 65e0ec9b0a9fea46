#pragma once
// The exponential Adams step's small matrix-vector products (its predictor with the predicted
// end's linear part, 15x30; its corrector, 10x5; the linear part A y, 5x10; internal to the
// core). At these sizes the cost is the instructions per
// column, which Eigen in a portable build (SSE2, no FMA, a loop per column) multiplies: one
// Google Highway kernel per size, fully unrolled, compiled for every SIMD target and picked at
// run time like the contact kernel, sums the columns with fused multiply-adds on the widest
// vectors the CPU has.
namespace bearing_sim::detail {

// out = base + m x for the column-major Rows x Cols matrix m (base null: out = m x); out must
// not overlap m, x or base. Defined for 15x30, 10x5 and 5x10.
template <int Rows, int Cols>
void multiply_add(const double* m, const double* x, const double* base, double* out);

// The same for any size (sizes not constants: not unrolled): the flexible ring's Adams step
// (50 x 50 and 50 x 100 for the CT ring's 25 coordinates).
void multiply_add(int rows, int cols, const double* m, const double* x, const double* base, double* out);

}  // namespace bearing_sim::detail
