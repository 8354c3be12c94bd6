// Incremental LDLᵀ of the clamped set: one row in, one row out, never a refactorisation.
//
// Appending row m to A = L D Lᵀ: with y = L⁻¹ a (a = the new row against the old ones),
//     L_m = (D⁻¹ y)ᵀ,  d_m = A_mm − yᵀ D⁻¹ y,
// and d_m is the Schur complement of the new row, positive exactly when the grown matrix is
// positive definite. Removing row p leaves L's leading block and the rows below p in place,
// except that the trailing block must absorb what row p contributed:
//     L₃₃' D₃' L₃₃'ᵀ = L₃₃ D₃ L₃₃ᵀ + d_p l l ᵀ,   l = L[p+1:, p],
// a rank-one update with positive weight, done here with the stable recurrence of Gill, Golub,
// Murray and Saunders (1974, method C1) reorganised row by row so that it reads L row-major.

#include "dynamics/lcp_internal.h"

#include <cstring>

namespace af::lcp {

void Ldlt::reserve(int n) {
    const std::size_t cells = static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
    if (l_.size() < cells) {
        l_.resize(cells);
    }
    if (d_.size() < static_cast<std::size_t>(n)) {
        d_.resize(n);
        invD_.resize(n);
    }
}

void Ldlt::reset(int stride) {
    stride_ = stride;
    size_ = 0;
}

void Ldlt::forward(Real* v) const {
    for (int r = 1; r < size_; ++r) {
        v[r] -= dot(row(r), v, r);
    }
}

void Ldlt::backward(Real* v) const {
    // Column form of the upper-triangular solve, so each step reads one contiguous row of L.
    for (int r = size_ - 1; r > 0; --r) {
        axpy(v, -v[r], row(r), r);
    }
}

void Ldlt::scale(Real* v) const {
    if (size_ > 0) {
        VecMap(v, size_).array() *= ConstVecMap(invD_.data(), size_).array();
    }
}

void Ldlt::solve(Real* v) const {
    forward(v);
    scale(v);
    backward(v);
}

bool Ldlt::appendForwardSolved(const Real* y, Real diag, Real minPivot) {
    const int m = size_;
    Real* lm = rowMut(m);
    Real  sum = 0;
    if (m > 0) {
        VecMap(lm, m) = ConstVecMap(y, m).cwiseProduct(ConstVecMap(invD_.data(), m));
        sum = dot(y, lm, m);
    }
    const Real d = diag - sum;
    if (!(d > minPivot)) {  // written so that NaN refuses too
        return false;
    }
    d_[m] = d;
    invD_[m] = 1 / d;
    size_ = m + 1;
    return true;
}

bool Ldlt::append(const Real* a, Real diag, Real minPivot, Real* scratch) {
    if (size_ > 0) {  // an empty row may come with a null pointer
        std::memcpy(scratch, a, sizeof(Real) * static_cast<std::size_t>(size_));
        forward(scratch);
    }
    return appendForwardSolved(scratch, diag, minPivot);
}

void Ldlt::remove(int p, Real* scratch) {
    const int m = size_;
    Real* z = scratch;         // the update vector, consumed row by row
    Real* zAt = scratch + m;   // z_j as it stood when column j was reached
    Real* beta = scratch + 2 * m;
    Real  alpha = d_[p];
    for (int r = p + 1; r < m; ++r) {
        z[r] = row(r)[p];
    }
    for (int r = p + 1; r < m; ++r) {
        Real* lr = rowMut(r);
        Real  zr = z[r];
        for (int j = p + 1; j < r; ++j) {
            zr -= zAt[j] * lr[j];
            lr[j] += beta[j] * zr;
        }
        const Real dOld = d_[r];
        const Real dNew = dOld + alpha * zr * zr;
        beta[r] = zr * alpha / dNew;
        alpha = dOld * alpha / dNew;
        zAt[r] = zr;

        // Row r becomes row r − 1, without column p.
        Real* dst = rowMut(r - 1);
        std::memmove(dst, lr, sizeof(Real) * static_cast<std::size_t>(p));
        std::memmove(dst + p, lr + p + 1, sizeof(Real) * static_cast<std::size_t>(r - 1 - p));
        d_[r - 1] = dNew;
        invD_[r - 1] = 1 / dNew;
    }
    size_ = m - 1;
}

}  // namespace af::lcp
