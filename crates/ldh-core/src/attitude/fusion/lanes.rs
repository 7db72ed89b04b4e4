//! Four filters of the bank side by side (structure of arrays), so that one step of the bank
//! is one pass of 4-wide arithmetic that the compiler vectorises (issue 17 item 3).
//!
//! [`L4`] is four `f64`, one per filter, with the arithmetic operators applied lane by lane:
//! each lane computes exactly the IEEE operations the scalar code computes, in the same order
//! (no fused multiply-add: Rust never contracts), so every filter's numbers are those of the
//! scalar filter bit for bit. Operations the lanes cannot share (sin/cos, logarithms, the
//! rare branches of `wrap`) go lane by lane through the scalar functions. The products and
//! steps of the bank are written once, generic over [`Num`] (`f64` or [`L4`]), so the same
//! code is tested against nalgebra on `f64` and runs on four filters at a time.

use std::ops::{Add, Div, Mul, Neg, Sub};

/// Number of filters per [`L4`].
pub(super) const LANES: usize = 4;

/// `[f(0), …, f(N − 1)]`: `std::array::from_fn` by an index loop, which is inlined into the
/// AVX2 clones of the bank's steps (`from_fn` was left as a call, compiled for SSE2).
#[inline(always)]
pub(super) fn array<T: Copy + Default, const N: usize>(mut f: impl FnMut(usize) -> T) -> [T; N] {
    let mut out = [T::default(); N];
    for (i, o) in out.iter_mut().enumerate() {
        *o = f(i);
    }
    out
}

/// A number type the bank's arithmetic is generic over: `f64` (one filter) or [`L4`].
pub(super) trait Num:
    Copy
    + Default
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// The value in every lane.
    fn splat(v: f64) -> Self;
    /// [`super::wrap`] in every lane.
    fn wrap(self) -> Self;
    /// `f64::sqrt` in every lane (IEEE, correctly rounded).
    fn sqrt(self) -> Self;
}

impl Num for f64 {
    #[inline(always)]
    fn splat(v: f64) -> f64 {
        v
    }
    #[inline(always)]
    fn wrap(self) -> f64 {
        super::wrap(self)
    }
    #[inline(always)]
    fn sqrt(self) -> f64 {
        f64::sqrt(self)
    }
}

/// Four `f64`, one per filter of a group of the bank.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C, align(32))]
pub(super) struct L4(pub(super) [f64; LANES]);

impl L4 {
    /// `f` applied to every lane.
    #[inline(always)]
    pub(super) fn map(self, f: impl Fn(f64) -> f64) -> L4 {
        L4([f(self.0[0]), f(self.0[1]), f(self.0[2]), f(self.0[3])])
    }

    /// `f` applied lane by lane to two operands.
    #[inline(always)]
    pub(super) fn zip(self, o: L4, f: impl Fn(f64, f64) -> f64) -> L4 {
        L4([
            f(self.0[0], o.0[0]),
            f(self.0[1], o.0[1]),
            f(self.0[2], o.0[2]),
            f(self.0[3], o.0[3]),
        ])
    }

    /// Lane by lane: `a` where `mask`, else `b`.
    #[inline(always)]
    pub(super) fn select(mask: [bool; LANES], a: L4, b: L4) -> L4 {
        let pick = |i: usize| if mask[i] { a.0[i] } else { b.0[i] };
        L4([pick(0), pick(1), pick(2), pick(3)])
    }
}

macro_rules! lanewise {
    ($tr:ident, $f:ident, $op:tt) => {
        impl $tr for L4 {
            type Output = L4;
            #[inline(always)]
            fn $f(self, o: L4) -> L4 {
                L4([
                    self.0[0] $op o.0[0],
                    self.0[1] $op o.0[1],
                    self.0[2] $op o.0[2],
                    self.0[3] $op o.0[3],
                ])
            }
        }
    };
}
lanewise!(Add, add, +);
lanewise!(Sub, sub, -);
lanewise!(Mul, mul, *);
lanewise!(Div, div, /);

impl Neg for L4 {
    type Output = L4;
    #[inline(always)]
    fn neg(self) -> L4 {
        L4([-self.0[0], -self.0[1], -self.0[2], -self.0[3]])
    }
}

impl Num for L4 {
    #[inline(always)]
    fn splat(v: f64) -> L4 {
        L4([v; LANES])
    }
    #[inline(always)]
    fn wrap(self) -> L4 {
        // the common case (every |a| < 3, returned unchanged) without a branch per lane
        let a = self.0;
        if a[0].abs() < 3.0 && a[1].abs() < 3.0 && a[2].abs() < 3.0 && a[3].abs() < 3.0 {
            self
        } else {
            self.map(super::wrap)
        }
    }
    #[inline(always)]
    fn sqrt(self) -> L4 {
        self.map(f64::sqrt)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lanes_compute_what_each_scalar_computes() {
        let a = L4([1.5, -3.25, 1e-300, 7.0]);
        let b = L4([0.1, 2.0, -1e300, -0.0]);
        for (got, f) in [
            (a + b, (|x, y| x + y) as fn(f64, f64) -> f64),
            (a - b, |x, y| x - y),
            (a * b, |x, y| x * y),
            (a / b, |x, y| x / y),
        ] {
            for i in 0..LANES {
                assert_eq!(got.0[i].to_bits(), f(a.0[i], b.0[i]).to_bits());
            }
        }
        let w = L4([0.5, 3.5, -7.0, 2.9]).wrap();
        for (i, x) in [0.5, 3.5, -7.0, 2.9].into_iter().enumerate() {
            assert_eq!(w.0[i].to_bits(), super::super::wrap(x).to_bits());
        }
        let s = L4::select([true, false, true, false], a, b);
        assert_eq!(s.0, [1.5, 2.0, 1e-300, -0.0]);
        assert_eq!((-a).0, [-1.5, 3.25, -1e-300, -7.0]);
    }
}
