//! Values given as expressions of x, y (initial coordinates of a node or an integration
//! point) and t (time), e.g. `dx = "1e-3*x/sqrt(x^2+y^2)"`: compiled once when the case
//! is loaded, evaluated at every point and time.
//!
//! | file | what |
//! |---|---|
//! | `mod.rs` | `Expr`: compile (errors with the position), evaluate |
//! | `scan.rs` | a token scan that places syntax errors (exmex's messages name no position) |
//! | `value.rs` | `Value`: a number or an expression string in the case file |
//!
//! The crate is `exmex`: it compiles a string once into a flat list of operators and
//! operands and evaluates it from a slice of variable values, with no allocation or name
//! look-up per evaluation (≈ 70 ns for `1e-3*x/sqrt(x^2+y^2)`, two `powf` included: 0.07 s
//! per million nodes, unit test `evaluation_is_cheap`), it is maintained, and its operators are the usual float
//! functions. `evalexpr` walks a tree and looks each variable up by name in a context at
//! every evaluation, and computes `1/2` in integers (0); `fasteval` and `meval` are fast
//! enough but have had no release for years. Two gaps of exmex are filled here: its
//! default literals have no exponent (`1e-3` would read as `1`, `e`, `-3`), so numbers use
//! our own pattern; and its syntax errors name no position, so a scan of our own finds it.

mod scan;
mod value;

pub use value::{Compiled, Value};

use crate::error::{Error, Result};
use exmex::{Express, FlatEx, FloatOpsFactory, MatchLiteral};

use std::sync::Arc;

exmex::literal_matcher_from_pattern!(Number, r"^([0-9]+\.?[0-9]*|\.[0-9]+)([eE][+-]?[0-9]+)?");

type Flat = FlatEx<f64, FloatOpsFactory<f64>, Number>;

/// The variables an expression may use, in exmex's (alphabetical) order of evaluation.
const VARIABLES: [&str; 3] = ["t", "x", "y"];

/// A compiled expression of (some of) t, x, y.
#[derive(Clone)]
pub struct Expr {
    text: String,
    flat: Arc<Flat>,
    /// For each variable of `flat`, in its order, the index in `VARIABLES`.
    slots: Vec<usize>,
}

impl std::fmt::Debug for Expr {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Expr({:?})", self.text)
    }
}

impl PartialEq for Expr {
    fn eq(&self, other: &Self) -> bool {
        self.text == other.text
    }
}

impl Expr {
    /// Compiles `text`; `allowed` are the variables it may use (of x, y, t). Errors start
    /// with `what` (the entry and key, e.g. `[[displacement]] 2 on 'Inner': dx`) and give
    /// the position (1-based character) of the fault.
    pub fn parse(text: &str, allowed: &[&str], what: &str) -> Result<Expr> {
        let fail = |msg: String| Error::model(format!("{what} = \"{text}\": {msg}"));
        let fail_at = |pos: usize, msg: String| {
            Error::model(format!("{what} = \"{text}\", character {pos}: {msg}"))
        };
        let list = allowed.join(", ");
        // names first: an unknown name is the likeliest fault and exmex would take it for
        // a variable (or reject the call of an unknown function with a vaguer message)
        for (pos, name) in scan::names(text) {
            let known = allowed.contains(&name.as_str()) || scan::is_function(&name);
            if !known && !scan::is_constant(&name) {
                let hint = if VARIABLES.contains(&name.as_str()) {
                    " here".to_string()
                } else {
                    String::new()
                };
                return Err(fail_at(
                    pos,
                    format!(
                        "unknown name '{name}'; the variables{hint} are {list} (functions: {}; \
                         constants: PI, E)",
                        scan::FUNCTIONS.join(", ")
                    ),
                ));
            }
        }
        scan::check(text).map_err(|(pos, msg)| match pos {
            0 => fail(msg),
            _ => fail_at(pos, msg),
        })?;
        let flat = <Flat as Express<f64>>::parse(text)
            .map_err(|e| fail(format!("cannot be read: {}", e.msg())))?;
        let slots = flat
            .var_names()
            .iter()
            .map(|v| VARIABLES.iter().position(|k| k == v))
            .collect::<Option<Vec<usize>>>()
            .ok_or_else(|| fail(format!("uses a name that is not one of {list}")))?;
        Ok(Expr {
            text: text.to_string(),
            flat: Arc::new(flat),
            slots,
        })
    }

    pub fn text(&self) -> &str {
        &self.text
    }

    /// Whether the expression depends on time.
    pub fn uses_t(&self) -> bool {
        self.slots.contains(&0)
    }

    /// The value at point `x` and time `t` (NaN where undefined, e.g. `sqrt(-1)`).
    #[inline]
    pub fn eval(&self, x: [f64; 2], t: f64) -> f64 {
        let all = [t, x[0], x[1]];
        let mut v = [0.0; 3];
        for (i, &s) in self.slots.iter().enumerate() {
            v[i] = all[s];
        }
        self.flat.eval(&v[..self.slots.len()]).unwrap_or(f64::NAN)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const XYT: [&str; 3] = ["x", "y", "t"];

    fn e(s: &str) -> Expr {
        Expr::parse(s, &XYT, "test").unwrap_or_else(|e| panic!("{s}: {e}"))
    }

    #[test]
    fn values_match_rust_arithmetic() {
        let (x, y, t) = (0.7_f64, -1.3_f64, 2.5_f64);
        let cases: [(&str, f64); 18] = [
            ("1e-3*x/sqrt(x^2+y^2)", 1e-3 * x / (x * x + y * y).sqrt()),
            ("2.5E+2 * y", 250.0 * y),
            (".5*t", 0.5 * t),
            ("x - y - t", x - y - t),
            ("x / y / t", x / y / t),
            ("x / y * t", x / y * t),
            ("x * y / t", x * y / t),
            ("x - y + t", x - y + t),
            ("-(x^2)", -(x * x)),
            ("(-x)^2", x * x),
            ("y - x^2", y - x * x),
            ("2^(3^2)", 512.0),
            ("x^2*y^2", x * x * y * y),
            ("2^-1", 0.5),
            ("atan2(y, x)", y.atan2(x)),
            (
                "cos(PI*t)*exp(-x)",
                (std::f64::consts::PI * t).cos() * (-x).exp(),
            ),
            ("min(x, y) + max(x, t)", x.min(y) + x.max(t)),
            ("42", 42.0),
        ];
        for (s, want) in cases {
            let got = e(s).eval([x, y], t);
            assert!(
                (got - want).abs() <= 1e-15 * want.abs().max(1.0),
                "{s}: {got} != {want}"
            );
        }
        assert!(e("x*t").uses_t() && !e("x*y").uses_t());
    }

    #[test]
    fn errors_name_the_fault_and_its_position() {
        let msg = |s: &str, allowed: &[&str]| {
            Expr::parse(s, allowed, "[[force]] 1 on 'A': fx")
                .unwrap_err()
                .to_string()
        };
        let head = "[[force]] 1 on 'A': fx = \"1e-3*z\", character 6: unknown name 'z'; the";
        assert!(msg("1e-3*z", &XYT).starts_with(head));
        for (text, allowed, want) in [
            (
                "2*x",
                &["t"][..],
                "character 3: unknown name 'x'; the variables here are t",
            ),
            ("sqr(x)", &XYT, "character 1: unknown name 'sqr'"),
            ("(x+1", &XYT, "character 1: '(' is not closed"),
            ("x+1)", &XYT, "character 4: ')' closes nothing"),
            (
                "x*",
                &XYT,
                "character 2: the expression ends with an operator",
            ),
            ("x**2", &XYT, "character 3: '*' follows an operator"),
            ("*x", &XYT, "character 1: '*' has no left operand"),
            (
                "1 + -x^2",
                &XYT,
                "character 5: a minus sign before a power is ambiguous",
            ),
            (
                "-sin(x)^2",
                &XYT,
                "character 1: a minus sign before a power",
            ),
            (
                "2^3^2",
                &XYT,
                "character 4: a power of a power is ambiguous",
            ),
            (
                "2 x",
                &XYT,
                "character 3: 'x' follows a value without an operator",
            ),
            ("x $ 2", &XYT, "character 3: '$' is not allowed"),
            (
                "sin x",
                &XYT,
                "character 1: function 'sin' needs its argument in parentheses",
            ),
            ("min(x)", &XYT, "character 6: 'min' takes two arguments"),
            ("", &XYT, "fx = \"\": the expression is empty"),
        ] {
            let m = msg(text, allowed);
            assert!(m.contains(want), "{text}: {m}");
        }
    }

    #[test]
    fn evaluation_is_cheap() {
        // issue 21: a 1M-node expression BC under 0.1 s per step
        let ex = e("1e-3*x/sqrt(x^2+y^2)");
        let points: Vec<[f64; 2]> = (0..1_000_000)
            .map(|i| {
                let a = i as f64 * 1e-6;
                [a.cos(), a.sin()]
            })
            .collect();
        let start = std::time::Instant::now();
        let mut s = 0.0;
        for &x in &points {
            s += ex.eval(x, 1.0);
        }
        let dt = start.elapsed().as_secs_f64();
        assert!(s.is_finite());
        eprintln!("1M evaluations of a radial displacement: {dt:.3} s");
        // generous for a loaded 2-core machine; the cost measured alone is ≈ 0.07 s
        assert!(dt < 0.5, "{dt} s for 1M evaluations");
    }
}
