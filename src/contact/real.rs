//! The number type of code that is differentiated exactly: `f64` for values, a forward-mode
//! dual number (num-dual's `DualSVec64`, derivatives in a fixed-size array) for tangents.
//! num-dual is maintained, covers the few functions needed (arithmetic, sqrt) and keeps
//! constants cheap (a dual without derivatives carries none), so no hand-written dual type.

use num_dual::{DualNum, DualStruct};

/// A real number or a dual number over f64.
pub trait Real: DualNum<Primitive = f64> + DualStruct<Real = f64> + Copy + Send + Sync {}

impl<T: DualNum<Primitive = f64> + DualStruct<Real = f64> + Copy + Send + Sync> Real for T {}

/// The real part (the value) of a real or dual number.
pub fn value<T: Real>(x: T) -> f64 {
    x.re()
}

/// The values of a vector's components.
pub fn values<T: Real>(x: [T; 2]) -> [f64; 2] {
    [value(x[0]), value(x[1])]
}

/// A constant: no derivatives.
pub fn constant<T: Real>(x: f64) -> T {
    T::from(x)
}
